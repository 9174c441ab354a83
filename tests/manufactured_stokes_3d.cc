// Order of accuracy in 3D: steady Stokes with the manufactured solution
// u = (sin(pi y) sin(pi z), sin(pi x) sin(pi z), sin(pi x) sin(pi y)),
// p = cos(pi x) cos(pi y) cos(pi z) on the unit cube, body force
// f = 2 pi^2 mu u + grad p. Expected orders close to 3 (u) and 2 (p).

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::string u =
    "sin(pi*y)*sin(pi*z); sin(pi*x)*sin(pi*z); sin(pi*x)*sin(pi*y)";
  const std::string p = "cos(pi*x)*cos(pi*y)*cos(pi*z)";
  const std::string f =
    "2*pi^2*sin(pi*y)*sin(pi*z) - pi*sin(pi*x)*cos(pi*y)*cos(pi*z);"
    "2*pi^2*sin(pi*x)*sin(pi*z) - pi*cos(pi*x)*sin(pi*y)*cos(pi*z);"
    "2*pi^2*sin(pi*x)*sin(pi*y) - pi*cos(pi*x)*cos(pi*y)*sin(pi*z)";
  std::string faces;
  for (const char *face : {"x min", "x max", "y min", "y max", "z min", "z max"})
    faces += std::string("subsection ") + face +
             "\n set type = function\n set function = " + u + "\nend\n";
  double old_u = 0, old_p = 0;
  for (unsigned int r = 1; r <= 3; ++r)
    {
      const std::string text =
        "set dimension = 3\n"
        "subsection simulation control\n set mode = steady stokes\nend\n"
        "subsection mesh\n set lower corner = 0, 0, 0\n set upper corner = "
        "1, 1, 1\n set cells per diameter = 0\n set global refinements = " +
        std::to_string(r) +
        "\nend\n"
        "subsection fluid\n set density = 1\n set viscosity = 1\n"
        " set body force = " + f + "\nend\n"
        "subsection boundary conditions\n" + faces + "end\n"
        "subsection postprocessing\n set exact velocity = " + u +
        "\n set exact pressure = " + p +
        "\nend\n"
        "subsection output\n set directory = results\n set write vtu = "
        "false\n set verbosity = quiet\nend\n";
      log_error_row(r, run_scene<3>(text), old_u, old_p);
    }
}
