// The steady Stokes-Brinkman solve and the BDF2 time march of the same
// penalized scene (2D: a disc in a channel, Re = 0.02) reach the same state:
// drag and pressure drop agree within 0.1 %.

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::string scene =
    "set dimension = 2\n"
    "subsection mesh\n set lower corner = 0, 0\n set upper corner = 4e-3, "
    "2e-3\n set cells per diameter = 8\nend\n"
    "subsection grains\n set source = list\n set list = 1.5e-3, 1e-3, 2.5e-4\n"
    "end\n"
    "subsection fluid\n set density = 1000\n set viscosity = 1e-3\n"
    " set theta = 1e4\nend\n"
    "subsection boundary conditions\n"
    " subsection x min\n  set type = velocity\n  set velocity = 4e-5, 0\n end\n"
    " subsection x max\n  set type = pressure\n end\n"
    " subsection y min\n  set type = symmetry\n end\n"
    " subsection y max\n  set type = symmetry\n end\n"
    "end\n"
    "subsection output\n set directory = results\n set write vtu = false\n"
    " set verbosity = quiet\nend\n";
  const auto steady = run_scene<2>(
    scene + "subsection simulation control\n set mode = steady stokes\n"
            " set time step = 1e-2\nend\n");
  // dt = 1e-2 s is also the penalization dt of the steady solve: the fixed
  // point of the BDF1 march is then exactly the steady solution (BDF2's has
  // 1.5 times the penalty coefficient). The viscous time rho L^2 / mu is 4 s.
  const auto transient = run_scene<2>(
    scene + "subsection simulation control\n set mode = transient\n"
            " set time step = 1e-2\n set end time = 20\n set time scheme = BDF1\n"
            " set steady state tolerance = 1e-9\nend\n");
  const double drag_difference =
    std::abs(transient.at("grain_force_x") / steady.at("grain_force_x") - 1);
  const double dp_difference =
    std::abs(transient.at("pressure_drop") / steady.at("pressure_drop") - 1);
  deallog << "drag: steady and transient agree within 0.1 %: "
          << (drag_difference < 1e-3 ? "yes" : "no") << std::endl;
  deallog << "pressure drop: steady and transient agree within 0.1 %: "
          << (dp_difference < 1e-3 ? "yes" : "no") << std::endl;
  deallog << "the march stopped at steady state before the end time: "
          << (transient.at("time") < 20 - 1e-9 ? "yes" : "no") << std::endl;
  deallog << "drag per length / (mu U) = " << std::setprecision(3)
          << steady.at("grain_force_x") / (1e-3 * 4e-5) << std::endl;
}
