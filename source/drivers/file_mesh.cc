#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/file_mesh.h>
#include <softsand/fluid/boundary_conditions.h>

#include <fstream>
#include <map>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /// The plural name of a kind of cell, as a mesher calls it.
      std::string
      cell_kind(const ReferenceCell &kind)
      {
        if (kind == ReferenceCells::Triangle)
          return "triangles";
        if (kind == ReferenceCells::Quadrilateral)
          return "quadrilaterals";
        if (kind == ReferenceCells::Tetrahedron)
          return "tetrahedra";
        if (kind == ReferenceCells::Pyramid)
          return "pyramids";
        if (kind == ReferenceCells::Wedge)
          return "prisms";
        if (kind == ReferenceCells::Hexahedron)
          return "hexahedra";
        return kind.to_string();
      }
    } // namespace


    template <int dim>
    void
    read_file_mesh(Triangulation<dim>              &triangulation,
                   const core::MeshParameters<dim> &mesh)
    {
      const std::string hypercubes = dim == 2 ? "quadrilaterals" : "hexahedra";
      const auto        read       = [&](Triangulation<dim> &destination) {
        std::ifstream in(mesh.mesh_file);
        try
          {
            GridIn<dim> grid_in;
            grid_in.attach_triangulation(destination);
            grid_in.read_msh(in);
          }
        catch (const std::exception &e)
          {
            base::throw_invalid_parameter(
              "mesh/mesh file",
              mesh.mesh_file,
              "deal.II could not read it as a gmsh mesh of " +
                std::to_string(dim) + "D " + hypercubes + " (" +
                base::error_message(e) + ")");
          }
      };

      // First into a serial triangulation, which takes simplices and mixed
      // meshes too: p4est takes only quadrilaterals/hexahedra and crashes
      // on anything else (a segfault, not an error).
      {
        Triangulation<dim> serial;
        read(serial);
        if (!serial.all_reference_cells_are_hyper_cube())
          {
            std::map<std::string, unsigned int> kinds;
            for (const auto &cell : serial.active_cell_iterators())
              ++kinds[cell_kind(cell->reference_cell())];
            std::string found;
            for (const auto &[kind, count] : kinds)
              found += (found.empty() ? "" : ", ") + std::to_string(count) +
                       " " + kind;
            base::throw_invalid_parameter(
              "mesh/mesh file",
              mesh.mesh_file,
              "its cells are " + found +
                ", but the octree mesh (p4est) takes only " + hypercubes +
                ": mesh the domain with " + hypercubes +
                " only (in gmsh: recombine the mesh; in 3D also "
                "Mesh.SubdivisionAlgorithm = 2)");
          }
        // gmsh gives boundary faces without a physical group the tag 0:
        // the whole boundary would take the conditions of 'x min', and
        // the run would end with misleading warnings (sealed pores).
        bool any_other_tag = false;
        for (const auto &face : serial.active_face_iterators())
          if (face->at_boundary() && face->boundary_id() != 0)
            any_other_tag = true;
        if (!any_other_tag)
          base::throw_invalid_parameter(
            "mesh/mesh file",
            mesh.mesh_file,
            "every boundary face has the boundary id 0, what gmsh writes for "
            "faces in no physical group (the file has none on its "
            "boundary): all of the boundary would take the conditions of "
            "'boundary conditions/x min'. Tag the boundary with physical "
            "groups (Physical Surface in 3D, Physical Curve in 2D): 0..." +
              std::to_string(2 * dim - 1) +
              " for the faces given conditions as 'x min', 'x max', ..., "
              "any other number for no-slip walls");
      }
      read(triangulation);

      const types::boundary_id wall =
        fluid::BoundaryConditions<dim>::cylinder_wall_id;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() > wall)
            cell->face(f)->set_boundary_id(wall);

      // The grains, walls and rings live in the box: the mesh must fit.
      const BoundingBox<dim> box = GridTools::compute_bounding_box(triangulation);
      const double tolerance = 1e-9 * box.side_length(0);
      for (unsigned int d = 0; d < dim; ++d)
        if (box.lower_bound(d) < mesh.lower_corner[d] - tolerance ||
            box.upper_bound(d) > mesh.upper_corner[d] + tolerance)
          {
            std::ostringstream extent, corners;
            extent << box.get_boundary_points().first << " to "
                   << box.get_boundary_points().second;
            corners << mesh.lower_corner << " to " << mesh.upper_corner;
            base::throw_invalid_parameter(
              "mesh/lower corner, mesh/upper corner",
              corners.str(),
              "the mesh of '" + mesh.mesh_file + "' spans " + extent.str() +
                " m: give a box that contains it");
          }
    }

    template void
    read_file_mesh(Triangulation<2> &, const core::MeshParameters<2> &);
    template void
    read_file_mesh(Triangulation<3> &, const core::MeshParameters<3> &);
  } // namespace drivers
} // namespace softsand
