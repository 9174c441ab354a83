// What a run given on the command line meets (softsand FILE.prm --set
// "subsection/entry=value" ..., through drivers::run_parameter_file):
// - --set changes an entry after the file is read, with the file's checks:
//   an unknown entry or subsection, a value its pattern refuses or one out
//   of range, and a malformed option stop with a message naming it;
// - parameters.prm (first line) and log.txt (first line) name the version
//   and the git commit;
// - a fresh run refuses an output directory that holds an earlier run's
//   results (naming output/directory and the ways on), unless it restarts
//   from the checkpoint there; the directory a refused input left (its
//   parameter files, no results) is taken;
// - parameter files that include each other, or themselves, stop with the
//   chain of files, before deal.II follows them into a stack overflow.
// A granular scene of one grain settling for 1e-4 s.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/version.h>
#include <softsand/core/parameters.h>
#include <softsand/drivers/run_parameter_file.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  const std::string scene =
    "set dimension = 3\n"
    "subsection simulation control\n set mode = granular\n"
    " set end time = 1e-4\nend\n"
    "subsection mesh\n set lower corner = 0, 0, 0\n"
    " set upper corner = 1e-3, 1e-3, 1e-3\nend\n"
    "subsection grains\n set source = list\n"
    " set list = 5e-4, 5e-4, 5e-4, 1e-4\nend\n"
    "subsection output\n set directory = owned\n set write vtu = false\n"
    " set verbosity = quiet\nend\n";

  void
  run(const std::string              &what,
      const std::string              &file,
      const std::vector<std::string> &settings = {})
  {
    try
      {
        softsand::drivers::run_parameter_file(file, MPI_COMM_WORLD, settings);
        deallog << what << ": ran" << std::endl;
      }
    catch (const std::exception &e)
      {
        deallog << what << ": " << softsand::base::error_message(e)
                << std::endl;
      }
  }

  /// The first line of @p file that matches @p pattern, blanks collapsed.
  std::string
  line_of(const std::string &file, const std::string &pattern)
  {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
      if (std::regex_search(line, std::regex(pattern)))
        return std::regex_replace(std::regex_replace(line,
                                                     std::regex(R"(\s+)"),
                                                     " "),
                                  std::regex(R"(^ | $)"),
                                  "");
    return "(none)";
  }

  std::string
  first_line(const std::string &file)
  {
    std::ifstream in(file);
    std::string   line;
    std::getline(in, line);
    return line;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  std::filesystem::remove_all("owned");
  std::filesystem::remove_all("restartable");
  std::ofstream("scene.prm") << scene;

  // --set, accepted and refused.
  run("--set dem/statistics interval and grains/list",
      "scene.prm",
      {"dem/statistics interval=7", " grains / list = 4e-4, 5e-4, 5e-4, 1e-4"});
  deallog << "parameters.prm: "
          << line_of("owned/parameters.prm", "set statistics interval") << "; "
          << line_of("owned/parameters.prm", "set list += [0-9]") << "; "
          << line_of("owned/parameters.prm", "^# --set") << std::endl;
  deallog << "version " << softsand::base::version()
          << ", the commit a hash or unknown: "
          << (std::regex_match(softsand::base::git_commit(),
                               std::regex(
                                 "[0-9a-f]{7,40}(-modified)?|unknown")) ?
                "yes" :
                "no")
          << std::endl;
  deallog << "parameters.prm starts with the version and commit: "
          << (first_line("owned/parameters.prm") ==
                  "# " + softsand::base::version_line() ?
                "yes" :
                "no")
          << std::endl;
  deallog << "log.txt starts with the version and commit: "
          << (first_line("owned/log.txt") == softsand::base::version_line() ?
                "yes" :
                "no")
          << std::endl;

  std::filesystem::remove_all("owned");
  run("--set unknown entry", "scene.prm", {"fluid/viscousity=1"});
  run("--set unknown subsection", "scene.prm", {"fluidd/viscosity=1"});
  run("--set value of the wrong type", "scene.prm", {"fluid/density=water"});
  run("--set value outside the pattern", "scene.prm", {"fluid/theta=-1"});
  run("--set value out of range", "scene.prm", {"fluid/viscosity=0"});
  run("--set without =", "scene.prm", {"fluid/viscosity"});
  run("--set with an empty subsection", "scene.prm", {"fluid//viscosity=1"});
  run("--set dimension = 4", "scene.prm", {"dimension=4"});

  // The output directory of one run.
  run("a grain outside the box (refused by the scene)",
      "scene.prm",
      {"grains/list=5e-4, 5e-4, 2e-3, 1e-4"});
  run("a fresh run into the directory that refused input left", "scene.prm");
  run("a second fresh run into it", "scene.prm");
  run("a second run, restart = true, no checkpoint there",
      "scene.prm",
      {"simulation control/restart=true"});
  run("a run with checkpoints",
      "scene.prm",
      {"output/directory=restartable",
       "simulation control/checkpoint interval=20"});
  run("its restart to 2e-4 s",
      "scene.prm",
      {"output/directory=restartable",
       "simulation control/checkpoint interval=20",
       "simulation control/restart=true",
       "simulation control/end time=2e-4"});
  const auto rows = read_statistics("restartable/statistics.txt");
  deallog << "restarted run's last time / 1e-4 s: " << std::setprecision(3)
          << rows.at("time").back() / 1e-4 << std::endl;

  // Include cycles.
  std::ofstream("self.prm") << "include self.prm\n";
  std::ofstream("a.prm") << "set dimension = 3\ninclude b.prm # the rest\n";
  std::ofstream("b.prm") << "subsection fluid\nend\n  include   a.prm\n";
  std::ofstream("c.prm") << "include a.prm\n";
  std::ofstream("d.prm") << "include scene.prm\ninclude scene.prm\n";
  run("a file that includes itself", "self.prm");
  run("two files that include each other", "a.prm");
  run("a file that includes two that include each other", "c.prm");
  try
    {
      softsand::core::check_include_cycles("d.prm");
      deallog << "a file included twice (no cycle): accepted" << std::endl;
    }
  catch (const std::exception &e)
    {
      deallog << "a file included twice (no cycle): "
              << softsand::base::error_message(e) << std::endl;
    }
}
