#ifndef softsand_drivers_cylinder_mesh_h
#define softsand_drivers_cylinder_mesh_h

#include <deal.II/grid/tria.h>

#include <softsand/core/mesh_parameters.h>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    /**
     * The coarse mesh of mesh/geometry = cylinder: a disc (GridGenerator's
     * balanced ball refined twice on its circle, then flattened: an
     * inscribed 32-gon, 192 cells) extruded along mesh/cylinder axis in
     * slices about as long as its cells are wide, centred in the box. Its
     * ends carry the box faces' boundary ids (z min and z max for an axis
     * along z), its mantle BoundaryConditions::cylinder_wall_id. No
     * manifold: refined cells are halves of their parents, so that hanging
     * faces match and the discrete flow conserves mass.
     */
    void
    make_cylinder_mesh(Triangulation<3> &triangulation,
                       const core::MeshParameters<3> &mesh);
  } // namespace drivers
} // namespace softsand

#endif
