// A sphere settling in a closed square duct (parameters/settling_sphere.prm,
// quasi-steady Stokes fluid, rigid-node solids; here 4 cells per diameter):
// the coupled loop reaches the terminal state, where the fluid force balances
// weight minus buoyancy (rho_s - rho_f) V g within 1 % (the rigid node set
// changes by whole nodes as the sphere moves: the force jitters by 0.4 % at
// this resolution), and the terminal
// velocity is within 5 % of Stokes' slowed by the duct walls,
// v = (1 - 1.903 d / L) (rho_s - rho_f) g d^2 / (18 mu) (the scene's 8 cells
// per diameter give +0.4 %, doc/validation_coupled.md).

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const auto r = run_scene<3>(
    scene_text("settling_sphere") +
    "subsection mesh\n set cells per diameter = 4\nend\n");
  const double d = 1e-3, g = 9.81, mu = 1, rho_s = 2650, rho_f = 1000;
  const double weight = (rho_s - rho_f) * M_PI * d * d * d / 6 * g;
  const double v_stokes = (rho_s - rho_f) * g * d * d / (18 * mu);
  const double v_wall   = (1 - 1.903 * 0.1) * v_stokes;
  const double v        = -r.at("grain0_vz");
  deallog << "fluid force balances weight - buoyancy within 1 %: "
          << (std::abs(r.at("grain_force_z") / weight - 1) < 1e-2 ? "yes" :
                                                                  "no")
          << std::endl;
  deallog << "terminal velocity within 5 % of the wall-corrected Stokes: "
          << (std::abs(v / v_wall - 1) < 0.05 ? "yes" : "no") << std::endl;
  deallog << "v / v_Stokes = " << std::setprecision(2) << v / v_stokes
          << std::endl;
}
