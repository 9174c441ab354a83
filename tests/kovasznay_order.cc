// Order of accuracy of the steady Navier-Stokes solver (Newton, Taylor-Hood
// Q2-Q1) on Kovasznay flow at Re = 40: L2 errors under uniform refinement
// and the observed orders (expected close to 3 for velocity, 2 for
// pressure).

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::string u = "1 - exp(L*x)*cos(2*pi*y); L/(2*pi)*exp(L*x)*sin(2*pi*y)";
  const std::string p = "0.5*(1 - exp(2*L*x))";
  auto with_lambda = [](std::string s) {
    const std::string lambda = "(20 - sqrt(400 + 4*pi^2))";
    for (std::size_t k = s.find('L'); k != std::string::npos; k = s.find('L'))
      s.replace(k, 1, lambda);
    return s;
  };
  std::string faces;
  for (const char *f : {"x min", "x max", "y min", "y max"})
    faces += std::string("subsection ") + f +
             "\n set type = function\n set function = " + with_lambda(u) +
             "\nend\n";
  double old_u = 0, old_p = 0;
  for (unsigned int r = 2; r <= 5; ++r)
    {
      const std::string text =
        "set dimension = 2\n"
        "subsection simulation control\n set mode = steady navier stokes\nend\n"
        "subsection mesh\n set lower corner = -0.5, 0\n set upper corner = "
        "1.5, 2\n set cells per diameter = 0\n set global refinements = " +
        std::to_string(r) +
        "\nend\n"
        "subsection fluid\n set density = 1\n set viscosity = 0.025\nend\n"
        "subsection boundary conditions\n" +
        faces +
        "end\n"
        "subsection postprocessing\n set exact velocity = " + with_lambda(u) +
        "\n set exact pressure = " + with_lambda(p) +
        "\nend\n"
        "subsection output\n set directory = results\n set write vtu = "
        "false\n set verbosity = quiet\nend\n";
      log_error_row(r, run_scene<2>(text), old_u, old_p);
    }
}
