// Checkpoint and restart of a coupled run: a sphere thrown across a uniform
// stream (transient BDF2 fluid, DEM, the mesh re-adapting as it moves) is
// run for 6 coupling steps at once, and for 3 steps with a checkpoint, then
// restarted from it for 3 more. The restarted run must continue exactly:
// the same grain position, velocity and fluid force at the end (relative
// difference below 1e-7), and its statistics table holds the 6 rows. Not bit
// for bit: FGMRES continues from a restored initial guess whose constrained
// entries differ in round-off, and the penalty force rho Theta (1 - vf) E /
// dt amplifies the solver's residual; with linear tolerance 1e-12 the runs
// agree to 2e-9 (with 1e-8, to 3e-5). The measured resistance (secant of
// two solves) that grains near walls or other grains use is checkpointed;
// used for this free grain it amplified the round-off tenfold per step.
// A stop signal (SIGUSR1, as mpirun passes on) before the first step ends a
// third run after that step with a checkpoint there; restarted, it must
// also equal the uninterrupted run.

#include <deal.II/base/mpi.h>

#include <softsand/base/stop_request.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  std::string
  scene(const std::string &directory, const double end_time,
        const bool restart)
  {
    std::ofstream("grain.txt") << "0 0 0 5e-4 0.1 0.02 0 0 0 0\n";
    std::ostringstream s;
    s << "set dimension = 3\n"
         "subsection simulation control\n set mode = coupled\n"
         " set time step = 1e-3\n set end time = "
      << end_time << "\n set checkpoint interval = 3\n set restart = "
      << (restart ? "true" : "false")
      << "\nend\n"
         "subsection coupling\n set readapt fraction = 0.2\nend\n"
         "subsection mesh\n set lower corner = -4e-3, -4e-3, -4e-3\n"
         " set upper corner = 4e-3, 4e-3, 4e-3\n set cells per diameter = 3\n"
         "end\n"
         "subsection grains\n set source = file\n set file = grain.txt\nend\n"
         "subsection dem\n subsection material\n  set density = 2650\n"
         " end\nend\n"
         "subsection fluid\n set density = 1000\n set viscosity = 1e-2\n"
         " set theta = 1e6\n set solid model = penalization\nend\n"
         "subsection fluid solver\n set linear tolerance = 1e-12\nend\n"
         "subsection boundary conditions\n"
         " subsection x min\n  set type = velocity\n"
         "  set velocity = 2e-3, 0, 0\n end\n"
         " subsection x max\n  set type = pressure\n end\n"
         "end\n"
         "subsection output\n set directory = "
      << directory
      << "\n set write vtu = true\n set verbosity = quiet\nend\n";
    return s.str();
  }

  /// The files of a PVD series, in order.
  std::vector<std::string>
  series_files(const std::string &pvd)
  {
    std::ifstream            in(pvd);
    std::vector<std::string> files;
    for (std::string line; std::getline(in, line);)
      if (const auto k = line.find("file=\""); k != std::string::npos)
        files.push_back(line.substr(k + 6, line.find('"', k + 6) - k - 6));
    return files;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const auto whole = run_scene<3>(scene("whole", 6e-3, false));
  run_scene<3>(scene("parts", 3e-3, false));
  const auto resumed = run_scene<3>(scene("parts", 6e-3, true));

  double largest = 0;
  for (const std::string name :
       {"grain0_x", "grain0_y", "grain0_vx", "grain0_vy", "grain_force_x",
        "grain_force_y",
        "pressure_drop"})
    largest = std::max(largest,
                       std::abs(resumed.at(name) / whole.at(name) - 1));
  deallog << "restarted run equals the uninterrupted one (1e-7): "
          << (largest < 1e-7 ? "yes" : "no") << std::endl;

  softsand::base::install_stop_handlers();
  std::raise(SIGUSR1);
  run_scene<3>(scene("signalled", 6e-3, false));
  deallog << "signalled run stopped on request: "
          << (softsand::base::stopped_on_request() ? "yes" : "no")
          << ", after " << read_statistics("signalled/statistics.txt")
                             .at("step")
                             .size()
          << " step(s), checkpoint written: "
          << (std::ifstream("signalled/checkpoint-1.dem") ? "yes" : "no")
          << std::endl;
  const auto continued = run_scene<3>(scene("signalled", 6e-3, true));
  double     difference = 0;
  for (const std::string name : {"grain0_x", "grain0_vx", "grain_force_x"})
    difference = std::max(difference,
                          std::abs(continued.at(name) / whole.at(name) - 1));
  deallog << "continued after the stop, equals the uninterrupted run (1e-7): "
          << (difference < 1e-7 ? "yes" : "no") << std::endl;
  deallog << "the mesh followed the grain: "
          << (whole.at("mesh_adaptations") > 0 ? "yes" : "no") << std::endl;
  deallog << "statistics rows after the restart: "
          << read_statistics("parts/statistics.txt").at("step").size()
          << std::endl;
  deallog << "grain velocity at 6 ms / m/s: " << std::setprecision(3)
          << whole.at("grain0_vx") << ' ' << whole.at("grain0_vy")
          << std::endl;
  // The restarted run continues the output series: no file of the first
  // part is overwritten or dropped from the .pvd.
  for (const std::string series : {"solution.pvd", "grains.pvd"})
    {
      const auto parts = series_files("parts/" + series);
      deallog << series << " after the restart: " << parts.size()
              << " steps (" << parts.front() << " to " << parts.back()
              << "), the same files as the uninterrupted run's: "
              << (parts == series_files("whole/" + series) ? "yes" : "no")
              << std::endl;
    }
}
