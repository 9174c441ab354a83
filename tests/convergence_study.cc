// Convergence-study mode (subsection "convergence study") on small 2D
// scenes, with observed orders that change if the physics breaks:
// * time step: a disc (rigid nodes) in a channel whose inflow ramps up
//   smoothly; the drag at t = 0.1 s converges with order 2 under BDF2 and
//   order 1 under BDF1, to the same Richardson estimate;
// * cells per diameter: the paper's penalization (cell-average void
//   fraction) converges monotonically with order about 1 (every cut cell
//   acts solid, the disc grows by about one cell);
// * global refinements: the Kovasznay velocity error (reference value 0)
//   falls with order about 3 (Taylor-Hood Q2).
// Bad study parameters stop with a message naming the entry.

#include <deal.II/base/mpi.h>

#include <softsand/drivers/convergence_study.h>
#include <softsand/base/parameter_tools.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

using softsand::drivers::ConvergenceStudy;

namespace
{
  const std::string channel =
    "set dimension = 2\n"
    "subsection mesh\n set lower corner = 0, 0\n set upper corner = 4e-3, "
    "2e-3\n set cells per diameter = 8\nend\n"
    "subsection grains\n set source = list\n set list = 1.5e-3, 1e-3, "
    "2.5e-4\nend\n"
    "subsection fluid\n set density = 1000\n set viscosity = 1e-3\nend\n"
    "subsection boundary conditions\n"
    " subsection x min\n  set type = function\n"
    "  set function = 4e-5*sin(pi*t/0.2)^2; 0\n end\n"
    " subsection x max\n  set type = pressure\n end\n"
    " subsection y min\n  set type = symmetry\n end\n"
    " subsection y max\n  set type = symmetry\n end\n"
    "end\n"
    "subsection output\n set directory = results\n set write vtu = false\n"
    " set verbosity = quiet\nend\n";

  std::vector<ConvergenceStudy<2>::Run>
  run_study(const std::string &text)
  {
    ParameterHandler prm;
    softsand::core::Parameters<2>::declare_parameters(prm);
    prm.parse_input_from_string(text);
    softsand::core::Parameters<2> parameters;
    parameters.parse_parameters(prm);
    ConvergenceStudy<2> study(parameters, MPI_COMM_WORLD);
    study.run();
    deallog << "monotone: " << (study.monotone() ? "yes" : "no") << std::endl;
    return study.runs();
  }

  /// One line per run: knob value, quantity / scale, change against the
  /// finest run and the observed order.
  void
  log_runs(const std::vector<ConvergenceStudy<2>::Run> &runs,
           const double                                 scale)
  {
    for (const auto &r : runs)
      {
        deallog << "value " << std::setprecision(5) << std::defaultfloat
                << r.value << " quantity " << std::scientific
                << std::setprecision(4) << r.quantity / scale << " change "
                << std::setprecision(2) << r.change_against_finest
                << std::fixed;
        if (std::isfinite(r.observed_order))
          deallog << " order " << std::setprecision(2) << r.observed_order;
        deallog << std::setprecision(6) << std::endl;
      }
  }

  void
  check_bad(const std::string &what, const std::string &study)
  {
    try
      {
        ParameterHandler prm;
        softsand::core::Parameters<2>::declare_parameters(prm);
        prm.parse_input_from_string(channel + study);
        softsand::core::Parameters<2> parameters;
        parameters.parse_parameters(prm);
        ConvergenceStudy<2>(parameters, MPI_COMM_WORLD).run();
        deallog << what << ": accepted (wrong)" << std::endl;
      }
    catch (const std::exception &e)
      {
        deallog << what << ": " << softsand::base::error_message(e)
                << std::endl;
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  // Drag per length scaled by mu U.
  const double force_scale = 1e-3 * 4e-5;

  double richardson[2] = {0, 0};
  for (const std::string scheme : {"BDF2", "BDF1"})
    {
      deallog << "time step, " << scheme << ", drag / (mu U) at t = 0.1 s"
              << std::endl;
      const auto runs =
        run_study(channel +
                  "subsection simulation control\n set mode = transient\n"
                  " set end time = 0.1\n set time scheme = " +
                  scheme +
                  "\nend\n"
                  "subsection fluid\n set solid model = rigid nodes\nend\n"
                  "subsection convergence study\n set knob = time step\n"
                  " set values = 0.02, 0.01, 0.005, 0.0025\n"
                  " set quantity = grain_force_x\nend\n");
      log_runs(runs, force_scale);
      const double p        = runs.back().observed_order;
      const int    expected = scheme == "BDF2" ? 2 : 1;
      deallog << "observed order within 0.4 of " << expected << ": "
              << (std::abs(p - expected) < 0.4 ? "yes" : "no") << std::endl;
      richardson[scheme == "BDF2" ? 0 : 1] = runs.back().richardson_estimate;
    }
  deallog << "BDF1 and BDF2 Richardson estimates agree within 0.1 %: "
          << (std::abs(richardson[1] / richardson[0] - 1) < 1e-3 ? "yes" : "no")
          << std::endl;

  deallog << "cells per diameter, penalization, steady drag / (mu U)"
          << std::endl;
  {
    const auto runs = run_study(
      channel +
      "subsection simulation control\n set mode = steady stokes\n"
      " set time step = 1e-2\nend\n"
      "subsection boundary conditions\n subsection x min\n"
      "  set type = velocity\n  set velocity = 4e-5, 0\n end\nend\n"
      "subsection fluid\n set solid model = penalization\n"
      " set theta = 1e4\nend\n"
      "subsection convergence study\n set knob = cells per diameter\n"
      " set values = 8, 16, 32, 64, 128\n set quantity = grain_force_x\nend\n");
    log_runs(runs, force_scale);
    bool first_order = true;
    for (const auto &r : runs)
      if (std::isfinite(r.observed_order))
        first_order =
          first_order && r.observed_order > 0.8 && r.observed_order < 1.7;
    deallog << "observed orders between 0.8 and 1.7: "
            << (first_order ? "yes" : "no") << std::endl;
  }

  deallog << "global refinements, Kovasznay velocity L2 error" << std::endl;
  {
    const std::string lambda = "(20 - sqrt(400 + 4*pi^2))";
    const std::string u = "1 - exp(" + lambda + "*x)*cos(2*pi*y); " + lambda +
                          "/(2*pi)*exp(" + lambda + "*x)*sin(2*pi*y)";
    std::string faces;
    for (const char *f : {"x min", "x max", "y min", "y max"})
      faces += std::string(" subsection ") + f +
               "\n  set type = function\n  set function = " + u + "\n end\n";
    const auto runs = run_study(
      "set dimension = 2\n"
      "subsection simulation control\n set mode = steady navier stokes\nend\n"
      "subsection mesh\n set lower corner = -0.5, 0\n set upper corner = 1.5, "
      "2\n set cells per diameter = 0\nend\n"
      "subsection fluid\n set density = 1\n set viscosity = 0.025\nend\n"
      "subsection boundary conditions\n" +
      faces +
      "end\n"
      "subsection postprocessing\n set exact velocity = " +
      u +
      "\nend\n"
      "subsection convergence study\n set knob = global refinements\n"
      " set values = 2, 3, 4, 5\n set quantity = velocity_l2_error\n"
      " set reference value = 0\nend\n"
      "subsection output\n set directory = results\n set write vtu = false\n"
      " set verbosity = quiet\nend\n");
    log_runs(runs, 1.);
    deallog << "observed order of the finest three within 0.5 of 3: "
            << (std::abs(runs.back().observed_order - 3) < 0.5 ? "yes" : "no")
            << std::endl;
  }

  check_bad("one value",
            "subsection convergence study\n set knob = theta\n"
            " set values = 1e6\nend\n");
  check_bad("repeated value",
            "subsection convergence study\n set knob = cells per diameter\n"
            " set values = 4, 8, 4\nend\n");
  check_bad("fractional refinements",
            "subsection convergence study\n set knob = global refinements\n"
            " set values = 1, 1.5\nend\n");
  check_bad("negative time step",
            "subsection convergence study\n set knob = time step\n"
            " set values = 1e-3, -1e-3\nend\n");
  check_bad("reference not a number",
            "subsection convergence study\n set knob = theta\n"
            " set values = 1e2, 1e4\n set reference value = abc\nend\n");
  check_bad("unknown quantity",
            "subsection convergence study\n set knob = theta\n"
            " set values = 1e2, 1e4\n set quantity = drag\nend\n"
            "subsection mesh\n set cells per diameter = 2\nend\n");
}
