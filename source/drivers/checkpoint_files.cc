#include <softsand/drivers/checkpoint_files.h>

#include <deal.II/base/exceptions.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    std::string
    checkpoint_base(const std::string &directory, const unsigned long step)
    {
      return directory + "/checkpoint-" + std::to_string(step);
    }


    void
    commit_checkpoint(const std::string &directory,
                      const unsigned long step,
                      const std::string &mode,
                      const std::string &info,
                      const MPI_Comm     comm)
    {
      namespace fs = std::filesystem;
      // Every rank's files are complete before the info names them.
      MPI_Barrier(comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          {
            std::ofstream out(directory + "/checkpoint.info.tmp");
            out << info << "mode " << mode << '\n';
          }
          fs::rename(directory + "/checkpoint.info.tmp",
                     directory + "/checkpoint.info");
          const std::string current = "checkpoint-" + std::to_string(step) + ".";
          for (const auto &entry : fs::directory_iterator(directory))
            {
              const std::string name = entry.path().filename().string();
              if (name.rfind("checkpoint-", 0) == 0 &&
                  name.rfind(current, 0) != 0)
                fs::remove(entry.path());
            }
        }
      MPI_Barrier(comm);
      // Fault injection for the restart tests: every rank dies by SIGKILL
      // (no clean-up, no flush) right after this checkpoint. Granular steps
      // take about a microsecond: no kill sent from outside lands between
      // two given checkpoints.
      if (const char *kill_step = std::getenv("SOFTSAND_SIGKILL_AFTER_CHECKPOINT"))
        if (step >= std::stoul(kill_step))
          std::raise(SIGKILL);
    }


    std::istringstream
    read_checkpoint_info(const std::string &directory, const std::string &mode)
    {
      const std::string name = directory + "/checkpoint.info";
      std::ifstream     in(name);
      AssertThrow(in.good(),
                  ExcMessage("simulation control/restart = true, but there "
                             "is no checkpoint <" +
                             name +
                             ">: run with a checkpoint interval > 0 first."));
      std::ostringstream contents;
      contents << in.rdbuf();
      const std::string text = contents.str();
      // The last line names the mode (checkpoints of earlier versions,
      // always coupled, have none).
      std::string written_by = "coupled";
      const auto  end        = text.find_last_not_of('\n');
      const auto  line_start =
        end == std::string::npos ? 0 : text.rfind('\n', end) + 1;
      if (text.compare(line_start, 5, "mode ") == 0)
        written_by = text.substr(line_start + 5, end + 1 - line_start - 5);
      AssertThrow(written_by == mode,
                  ExcMessage("simulation control/restart = true, but the "
                             "checkpoint <" +
                             name + "> was written by a " + written_by +
                             " run; this run's mode is " + mode +
                             ": restart with the parameters of that run."));
      return std::istringstream(text);
    }


    void
    check_checkpoint_info(const std::istream &info, const std::string &directory)
    {
      AssertThrow(!info.fail(),
                  ExcMessage("The checkpoint <" + directory +
                             "/checkpoint.info> is truncated or corrupt."));
    }


    std::ifstream
    open_checkpoint_file(const std::string &name)
    {
      std::ifstream in(name, std::ios::binary);
      AssertThrow(in.good(),
                  ExcMessage("The checkpoint <" + name +
                             "> is missing or unreadable."));
      return in;
    }
  } // namespace drivers
} // namespace softsand
