// mesh/geometry = file with a gmsh mesh of tetrahedra (or any cell that is
// not a hexahedron): p4est takes only hexahedra and crashed (segfault) on
// them. The file must be refused before p4est sees it, with a message
// naming mesh/mesh file, the file, the cells found and what is allowed; a
// mesh that mixes hexahedra and prisms likewise. A hexahedral mesh of the
// same box is still read (its run gives its cells); without physical
// groups on its faces (every boundary id 0, issue 55) it is refused.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>

#include <fstream>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  std::string
  scene(const std::string &mesh_file)
  {
    return "set dimension = 3\n"
           "subsection simulation control\n set mode = steady stokes\nend\n"
           "subsection mesh\n set geometry = file\n set mesh file = " +
           mesh_file +
           "\n set lower corner = 0, 0, 0\n set upper corner = 1, 1, 1\n"
           " set cells per diameter = 0\nend\n"
           "subsection boundary conditions\n subsection x min\n"
           "  set type = velocity\n  set velocity = 1e-3, 0, 0\n end\n"
           " subsection x max\n  set type = pressure\n end\nend\n"
           "subsection output\n set directory = results\n set write vtu = "
           "false\n set verbosity = quiet\nend\n";
  }

  void
  run(const std::string &what, const std::string &mesh_file)
  {
    try
      {
        const auto row = run_scene<3>(scene(mesh_file));
        deallog << what << ": accepted, cells "
                << static_cast<unsigned int>(row.at("cells")) << std::endl;
      }
    catch (const std::exception &e)
      {
        deallog << what << ": " << softsand::base::error_message(e)
                << std::endl;
      }
  }

  /// A gmsh 2.2 file with @p nodes ("x y z" each) and @p elements
  /// ("TYPE node node ..." each, 1-based nodes; "TYPE@TAG ..." gives the
  /// physical tag, 0 otherwise).
  void
  write_msh(const std::string              &name,
            const std::vector<std::string> &nodes,
            const std::vector<std::string> &elements)
  {
    std::ofstream out(name);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
        << nodes.size() << '\n';
    for (unsigned int k = 0; k < nodes.size(); ++k)
      out << k + 1 << ' ' << nodes[k] << '\n';
    out << "$EndNodes\n$Elements\n" << elements.size() << '\n';
    for (unsigned int k = 0; k < elements.size(); ++k)
      {
        std::istringstream words(elements[k]);
        std::string        type, rest;
        words >> type;
        std::getline(words, rest);
        std::string physical = "0";
        if (const auto at = type.find('@'); at != std::string::npos)
          {
            physical = type.substr(at + 1);
            type     = type.substr(0, at);
          }
        // Two tags: physical and elementary entity.
        out << k + 1 << ' ' << type << " 2 " << physical << " 1" << rest
            << '\n';
      }
    out << "$EndElements\n";
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // The unit cube as one hexahedron (gmsh type 5), as five tetrahedra
  // (type 4), and as a hexahedron beside two prisms (type 6).
  const std::vector<std::string> cube = {
    "0 0 0", "1 0 0", "1 1 0", "0 1 0", "0 0 1", "1 0 1", "1 1 1", "0 1 1"};
  // Its faces in physical groups 0..5 (x min, x max, ...), or in none.
  write_msh("hexahedron.msh",
            cube,
            {"5 1 2 3 4 5 6 7 8",
             "3@0 1 4 8 5",
             "3@1 2 3 7 6",
             "3@2 1 2 6 5",
             "3@3 4 3 7 8",
             "3@4 1 2 3 4",
             "3@5 5 6 7 8"});
  write_msh("untagged.msh", cube, {"5 1 2 3 4 5 6 7 8"});
  write_msh("tetrahedra.msh",
            cube,
            {"4 1 2 4 5", "4 2 3 4 7", "4 2 5 6 7", "4 4 5 7 8", "4 2 4 5 7"});
  write_msh("mixed.msh",
            {"0 0 0",
             "1 0 0",
             "1 1 0",
             "0 1 0",
             "0 0 0.5",
             "1 0 0.5",
             "1 1 0.5",
             "0 1 0.5",
             "0 0 1",
             "1 0 1",
             "1 1 1",
             "0 1 1"},
            {"5 1 2 3 4 5 6 7 8", "6 5 6 7 9 10 11", "6 5 7 8 9 11 12"});

  run("hexahedron", "hexahedron.msh");
  run("hexahedron without physical groups", "untagged.msh");
  run("tetrahedra", "tetrahedra.msh");
  run("hexahedron and prisms", "mixed.msh");
}
