// Two touching grains (d = 1.35 mm) between no-slip plates 1.5 d apart, 4
// cells per diameter, cell-average void fraction, three transient BDF steps
// of 0.25 ms from rest (rho 1000 kg/m^3, mu 0.01 Pa s, the small Hele-Shaw
// injection's fluid and step) with grain A moving and grain B at rest, the
// forces of the third step: A slides along B (0.1 m/s), approaches B (0.1 m/s),
// rotates about the plates' normal (0.1 m/s at its surface). The paper's
// penalization asks the Q2 nodes of the cells the grains share to follow
// two rigid motions, and the force of that conflict grows with Theta
// (printed at Theta = 1e4, 1e5, 1e6); the penalization limit gives each
// node one blended target, and relaxes continuity where those targets
// squeeze the fluid (fluid/squeeze relaxation; printed also without it).
// Every force (torque for the rotation) is printed as a ratio to the
// rigid-node model's for the same motion (pressure smoothing 1e-4, the
// default, for both). The rotating grain's net force is near zero by
// symmetry (rigid nodes: 1.3e-6 N, 3 % of its torque / R), so its ratio
// compares two small numbers.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/grid_generator.h>

#include <softsand/core/parameters.h>
#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_solid_field.h>
#include <softsand/fluid/penalized_navier_stokes.h>

#include <sstream>
#include <vector>

#include "tests.h"

using namespace softsand;

namespace
{
  constexpr double radius = 0.675e-3;
  constexpr double gap    = 3 * radius; // plate to plate
  constexpr double speed  = 0.1;

  enum class Motion
  {
    slide,
    approach,
    rotate
  };

  /// Force on A and on B, torque on A.
  struct Response
  {
    double force_a, force_b, torque_a;
  };

  Response
  solve(const std::string &model,
        const double       theta,
        const Motion       motion,
        const double       pressure_smoothing = 1e-4,
        const double       squeeze_relaxation = 100)
  {
    std::ostringstream text;
    text << "set dimension = 3\n"
            "subsection mesh\n set lower corner = -2.7e-3, -1.35e-3, 0\n"
            " set upper corner = 2.7e-3, 1.35e-3, "
         << gap
         << "\nend\n"
            "subsection fluid\n set density = 1000\n set viscosity = 0.01\n"
            " set theta = "
         << theta << "\n set solid model = " << model
         << "\n set free contact cells = false\n"
            " set rigid node pressure smoothing = "
         << pressure_smoothing << "\n set squeeze relaxation = "
         << squeeze_relaxation
         << "\nend\n"
            "subsection fluid solver\n set linear tolerance = 1e-10\nend\n"
            "subsection coupling\n set void fraction model = cell average\n"
            "end\n"
            "subsection boundary conditions\n";
    for (const std::string face : {"x min", "x max", "y min", "y max"})
      text << " subsection " << face << "\n  set type = pressure\n end\n";
    text << "end\n";
    ParameterHandler prm;
    core::Parameters<3>::declare_parameters(prm);
    prm.parse_input_from_string(text.str());
    core::Parameters<3> p;
    p.parse_parameters(prm);

    // 16 x 8 x 6 cells of d / 4.
    parallel::distributed::Triangulation<3> mesh(MPI_COMM_WORLD);
    GridGenerator::subdivided_hyper_rectangle(mesh,
                                              {16, 8, 6},
                                              Point<3>(-2.7e-3, -1.35e-3, 0),
                                              Point<3>(2.7e-3, 1.35e-3, gap),
                                              true);

    std::vector<dem::Grain<3>> grains(2);
    grains[0].center = Point<3>(-radius, 0, gap / 2);
    grains[1].center = Point<3>(radius, 0, gap / 2);
    for (auto &g : grains)
      g.radius = radius;
    if (motion == Motion::slide)
      grains[0].velocity[1] = speed;
    else if (motion == Motion::approach)
      grains[0].velocity[0] = speed;
    else
      grains[0].angular_velocity[2] = speed / radius;
    coupling::GrainSolidField<3> solids(grains, p.void_fraction);

    std::ostringstream quiet;
    ConditionalOStream pcout(quiet, false);
    TimerOutput timer(quiet, TimerOutput::never, TimerOutput::wall_times);
    fluid::PenalizedNavierStokes<3> fluid(
      mesh, p.fluid, p.fluid_solver, p.boundary_conditions, pcout, timer);
    fluid.set_solid_field(&solids);
    fluid.setup_dofs();
    // Three BDF steps of the coupled injection's length from rest, the
    // grains held where they are with their velocities imposed.
    const double time_step = 2.5e-4;
    fluid.start_time_stepping();
    for (unsigned int step = 1; step <= 3; ++step)
      {
        fluid.set_time(step * time_step);
        fluid.advance(time_step, 2);
      }
    const auto forces = coupling::compute_grain_forces(
      fluid,
      grains,
      coupling::ForceModel::penalization_reaction,
      MPI_COMM_WORLD);
    return {forces.force[0].norm(),
            forces.force[1].norm(),
            forces.torque[0].norm()};
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::pair<Motion, std::string> motions[] = {{Motion::slide, "slide"},
                                                    {Motion::approach,
                                                     "approach"},
                                                    {Motion::rotate, "rotate"}};
  for (const auto &[motion, name] : motions)
    {
      const Response rigid = solve("rigid nodes", 1e6, motion);
      const auto     log   = [&](const std::string &label, const Response &r) {
        // Two significant digits: the penalty's ratios span 1e3-1e6.
        deallog << name << ", " << label << ": F_A " << std::scientific
                << std::setprecision(1) << r.force_a / rigid.force_a << ", F_B "
                << r.force_b / rigid.force_b;
        if (motion == Motion::rotate)
          deallog << ", T_A " << r.torque_a / rigid.torque_a;
        deallog << " x rigid nodes" << std::fixed << std::setprecision(6)
                << std::endl;
      };
      for (const double theta : {1e4, 1e5, 1e6})
        {
          std::ostringstream label;
          label << "penalization, Theta " << std::scientific
                << std::setprecision(0) << theta << std::fixed;
          log(label.str(), solve("penalization", theta, motion));
        }
      log("penalization limit", solve("penalization limit", 1e6, motion));
      // The squeeze lives in the pressure of the cells whose velocity nodes
      // are all imposed: without the squeeze relaxation it reaches the
      // grains; more smoothing everywhere lessens it at the pack's
      // permeability's expense.
      log("penalization limit, squeeze relaxation 0",
          solve("penalization limit", 1e6, motion, 1e-4, 0));
      log("penalization limit, squeeze relaxation 0, pressure smoothing 1e-3",
          solve("penalization limit", 1e6, motion, 1e-3, 0));
    }
}
