#ifndef softsand_drivers_file_mesh_h
#define softsand_drivers_file_mesh_h

#include <deal.II/grid/tria.h>

#include <softsand/core/mesh_parameters.h>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    /**
     * The coarse mesh of mesh/geometry = file: the gmsh mesh of
     * mesh/mesh file, read by deal.II's GridIn (quadrilaterals in 2D,
     * hexahedra in 3D). Boundary tags 0..2 dim-1 keep their ids (the
     * conditions of x min ... z max); every other tag becomes
     * BoundaryConditions::cylinder_wall_id, a no-slip wall. Stops with a
     * message naming the parameter when the file cannot be read or the
     * mesh leaves the box between mesh/lower corner and mesh/upper corner,
     * the frame of the grains and walls.
     */
    template <int dim>
    void
    read_file_mesh(Triangulation<dim>              &triangulation,
                   const core::MeshParameters<dim> &mesh);
  } // namespace drivers
} // namespace softsand

#endif
