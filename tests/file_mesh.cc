// mesh/geometry = file: a gmsh mesh as the domain. The pipe of
// mesh/geometry = cylinder (radius R along z) is written as a .msh file
// with its mantle tagged 9 (any tag above 5 is a no-slip wall) and read
// back: Hagen-Poiseuille flow through it must give the same permeability
// as the built-in cylinder, K = q mu L / dp near R^2 / 8 (the inscribed
// 32-gon: 0.994 of the circle's area), and the fluid's push on the
// pressure faces (integrated over the mesh's faces, not the box's) must
// equal the built-in value; a uniform pressure added to the outlet
// (and so everywhere) must not change it. Then the messages for a missing file, a box
// that does not hold the mesh, and a flow-rate face on a mesh file.

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_out.h>
#include <deal.II/grid/tria.h>

#include <softsand/drivers/cylinder_mesh.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  const double R = 2.5e-4;

  std::string
  pipe(const std::string &geometry, const std::string &inlet_type,
       const std::string &extra = "")
  {
    std::ostringstream text;
    text << "set dimension = 3\n"
            "subsection simulation control\n set mode = steady stokes\nend\n"
            "subsection mesh\n set geometry = "
         << geometry
         << "\n set mesh file = pipe.msh\n"
            " set lower corner = -2.5e-4, -2.5e-4, 0\n"
            " set upper corner = 2.5e-4, 2.5e-4, 1e-3\n"
            " set cells per diameter = 0\nend\n"
            "subsection fluid\n set viscosity = 1e-3\nend\n"
            "subsection boundary conditions\n subsection z min\n  set type = "
         << inlet_type
         << "\n  set velocity = 0, 0, 1e-3\n  set flow rate = 1e-10\n"
            "  set pressure = 0\n end\n subsection z max\n"
            "  set type = pressure\n end\nend\n"
            "subsection postprocessing\n set flow axis = z\n"
            " set pressure drop planes = 3e-4, 7e-4\nend\n"
            "subsection output\n set directory = results\n set write vtu = "
            "false\n set verbosity = quiet\nend\n"
         << extra;
    return text.str();
  }

  void
  log_error(const std::string &what, const std::string &prm_text)
  {
    try
      {
        run_scene<3>(prm_text);
        deallog << what << ": no error" << std::endl;
      }
    catch (const std::exception &e)
      {
        std::string message = e.what();
        // The entry and the value named; the rest is prose.
        const auto entry = message.find("mesh/");
        const auto bc    = message.find("boundary conditions/");
        message = message.substr(std::min(entry, bc));
        message = message.substr(0, message.find('>'));
        deallog << what << ": " << message << std::endl;
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // The built-in cylinder's coarse mesh, its mantle retagged 9, as gmsh.
  {
    softsand::core::MeshParameters<3> m;
    m.lower_corner  = Point<3>(-R, -R, 0);
    m.upper_corner  = Point<3>(R, R, 1e-3);
    m.geometry      = softsand::core::MeshParameters<3>::Geometry::cylinder;
    m.cylinder_axis = 2;
    Triangulation<3> tria;
    softsand::drivers::make_cylinder_mesh(tria, m);
    for (const auto &face : tria.active_face_iterators())
      if (face->at_boundary() && face->boundary_id() == 6)
        face->set_boundary_id(9);
    GridOut grid_out;
    GridOutFlags::Msh flags(true, true);
    grid_out.set_flags(flags);
    std::ofstream out("pipe.msh");
    grid_out.write_msh(tria, out);
  }

  const double k_exact   = R * R / 8;
  const auto   builtin   = run_scene<3>(pipe("cylinder", "velocity"));
  const auto   from_file = run_scene<3>(pipe("file", "velocity"));
  for (const auto &[name, row] :
       {std::make_pair("cylinder", builtin), std::make_pair("file", from_file)})
    deallog << "geometry = " << name << ": cells "
            << static_cast<unsigned int>(row.at("cells"))
            << ", K / (R^2 / 8) = " << std::setprecision(4)
            << row.at("permeability") / k_exact
            << ", outflow / inflow = "
            << row.at("outflow_rate") / row.at("flow_rate") << std::endl;
  deallog << "file / cylinder: K " << std::setprecision(6)
          << from_file.at("permeability") / builtin.at("permeability")
          << ", boundary force z "
          << from_file.at("boundary_force_z") / builtin.at("boundary_force_z")
          << std::endl;

  // A uniform pressure added everywhere pushes on the outlet and, through
  // the reaction, on the inlet alike: no net force on the fluid's walls
  // when the pressure faces are integrated over the mesh.
  for (const auto &[name, row] :
       {std::make_pair("cylinder", builtin), std::make_pair("file", from_file)})
    {
      const auto raised = run_scene<3>(pipe(
        name,
        "velocity",
        "subsection boundary conditions\n subsection z max\n"
        "  set pressure = 1000\n end\nend\n"));
      deallog << "geometry = " << name
              << ", outlet raised by 1000 Pa: change of boundary force z / "
                 "(1000 Pa pi R^2) = "
              << std::fixed << std::setprecision(4)
              << (raised.at("boundary_force_z") - row.at("boundary_force_z")) /
                   (1000 * M_PI * R * R)
              << std::endl;
    }

  log_error("missing file",
            pipe("file", "velocity",
                 "subsection mesh\n set mesh file = no_such.msh\nend\n"));
  log_error("box too small",
            pipe("file", "velocity",
                 "subsection mesh\n set upper corner = 2.5e-4, 2.5e-4, "
                 "5e-4\nend\n"));
  log_error("flow rate on a mesh file", pipe("file", "flow rate"));
}
