#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/stop_request.h>
#include <softsand/core/parameters.h>
#include <softsand/drivers/run_parameter_file.h>

#include <chrono>
#include <iostream>
#include <string>
#include <thread>

namespace
{
  void
  print_usage()
  {
    std::cout
      << "Usage: softsand FILE.prm            run the scene in FILE.prm\n"
         "       mpirun -np N softsand FILE.prm\n"
         "       softsand --print-parameters [2|3]\n"
         "                                    print every parameter with its\n"
         "                                    documentation and default\n";
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
      if (argc > 2)
        {
          // Options after the file would otherwise be dropped without a
          // word: the run would not be the one asked for.
          if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            std::cerr << "softsand: error: unexpected argument '" << argv[2]
                      << "' after the parameter file " << argv[1]
                      << ": softsand takes one parameter file (change "
                         "entries in the file itself)."
                      << std::endl;
          print_usage();
          return 1;
        }
      try
        {
          softsand::base::install_stop_handlers();
          softsand::drivers::run_parameter_file(argv[1], MPI_COMM_WORLD);
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
