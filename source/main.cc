#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/stop_request.h>
#include <softsand/base/version.h>
#include <softsand/core/parameters.h>
#include <softsand/drivers/run_parameter_file.h>

#include <chrono>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace
{
  void
  print_usage()
  {
    std::cout
      << "Usage: softsand FILE.prm [--set \"SUBSECTION/ENTRY=VALUE\"]...\n"
         "                                    run the scene in FILE.prm, each\n"
         "                                    --set changing one entry after\n"
         "                                    the file is read\n"
         "       mpirun -np N softsand FILE.prm [--set ...]\n"
         "       softsand --print-parameters [2|3]\n"
         "                                    print every parameter with its\n"
         "                                    documentation and default\n"
         "       softsand --version           print the version and the git\n"
         "                                    commit it was built from\n";
  }

} // namespace


int
main(int argc, char *argv[])
{
  using namespace dealii;
  try
    {
      Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
      deallog.depth_console(0);

      if (argc < 2 || std::string(argv[1]) == "--help" ||
          std::string(argv[1]) == "-h")
        {
          print_usage();
          return argc < 2 ? 1 : 0;
        }
      if (std::string(argv[1]) == "--print-parameters")
        {
          ParameterHandler prm;
          if (argc > 2 && std::string(argv[2]) == "2")
            softsand::core::Parameters<2>::declare_parameters(prm);
          else
            softsand::core::Parameters<3>::declare_parameters(prm);
          prm.print_parameters(std::cout,
                               ParameterHandler::OutputStyle::PRM);
          return 0;
        }
      if (std::string(argv[1]) == "--version")
        {
          if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            std::cout << softsand::base::version_line() << std::endl;
          return 0;
        }
      // The parameter file, then --set options; anything else is refused
      // rather than dropped: the run would not be the one asked for.
      std::string              filename;
      std::vector<std::string> settings;
      std::string              argument_error;
      for (int k = 1; k < argc && argument_error.empty(); ++k)
        {
          const std::string argument = argv[k];
          if (argument == "--set")
            {
              if (k + 1 < argc)
                settings.emplace_back(argv[++k]);
              else
                argument_error = "--set needs \"SUBSECTION/ENTRY=VALUE\" "
                                 "after it";
            }
          else if (argument.rfind("--set=", 0) == 0)
            settings.push_back(argument.substr(6));
          else if (filename.empty() && argument.rfind("-", 0) != 0)
            filename = argument;
          else
            argument_error =
              "unexpected argument '" + argument + "'" +
              (filename.empty() ? std::string() :
                                  " after the parameter file " + filename) +
              ": softsand takes one parameter file and --set options";
        }
      if (argument_error.empty() && filename.empty())
        argument_error = "no parameter file given";
      if (!argument_error.empty())
        {
          if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            std::cerr << "softsand: error: " << argument_error << std::endl;
          print_usage();
          return 1;
        }
      try
        {
          softsand::base::install_stop_handlers();
          softsand::drivers::run_parameter_file(filename,
                                                MPI_COMM_WORLD,
                                                settings);
          if (softsand::base::stopped_on_request())
            return softsand::base::exit_code_stopped;
        }
      catch (const std::exception &e)
        {
          const unsigned int rank =
            Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
          // Input errors are found on every rank alike and rank 0 reports
          // them. A failure on other ranks only (a grain, a solver) must
          // be reported too: those ranks wait a moment, so that a common
          // failure is reported once (rank 0's abort ends them first).
          if (rank > 0)
            std::this_thread::sleep_for(std::chrono::seconds(2));
          std::cerr << "softsand: error: "
                    << (rank > 0 ? "(rank " + std::to_string(rank) + ") " :
                                   std::string())
                    << softsand::base::error_message(e) << std::endl;
          // A failure on some ranks only must not leave the others
          // waiting.
          if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
            MPI_Abort(MPI_COMM_WORLD, 1);
          return 1;
        }
    }
  catch (const std::exception &e)
    {
      std::cerr << "softsand: error: " << softsand::base::error_message(e) << std::endl;
      return 1;
    }
  return 0;
}
