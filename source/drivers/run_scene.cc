#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/coupled_scene.h>
#include <softsand/drivers/fluid_scene.h>
#include <softsand/drivers/granular_scene.h>
#include <softsand/drivers/run_scene.h>

#include <exception>
#include <filesystem>
#include <fstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /**
       * Run a scene of class Scene and return its results. An error is
       * caught while the scene still lives and thrown again once it is
       * gone: destroyed during the unwinding, its TimerOutput would print a
       * banner about skipped timings after the error, which must be the
       * last thing a user reads. The error also ends the run's log.txt.
       */
      template <class Scene, int dim>
      std::map<std::string, double>
      run_and_report(const core::Parameters<dim> &parameters,
                     const MPI_Comm               comm)
      {
        std::map<std::string, double> results;
        std::exception_ptr            error;
        {
          Scene scene(parameters, comm);
          try
            {
              scene.run();
              results = scene.results();
            }
          catch (...)
            {
              error = std::current_exception();
            }
        }
        if (!error)
          return results;
        const std::string log = parameters.output.directory + "/log.txt";
        if (Utilities::MPI::this_mpi_process(comm) == 0 &&
            std::filesystem::exists(log))
          try
            {
              std::rethrow_exception(error);
            }
          catch (const std::exception &e)
            {
              std::ofstream(log, std::ios::app)
                << "softsand: error: " << base::error_message(e) << std::endl;
            }
          catch (...)
            {}
        std::rethrow_exception(error);
      }
    } // namespace


    template <int dim>
    std::map<std::string, double>
    run_scene(const core::Parameters<dim> &parameters, const MPI_Comm comm)
    {
      using Mode      = core::SimulationControl::Mode;
      const Mode mode = parameters.simulation_control.mode;
      if (mode == Mode::granular || mode == Mode::coupled)
        {
          // The DEM is 3D.
          if constexpr (dim == 3)
            {
              if (mode == Mode::granular)
                return run_and_report<GranularScene>(parameters, comm);
              return run_and_report<CoupledScene>(parameters, comm);
            }
          else
            base::throw_invalid_parameter(
              "simulation control/mode",
              mode == Mode::granular ? "granular" : "coupled",
              mode == Mode::granular ?
                "granular scenes are 3D (set dimension = 3)" :
                "coupled (CFD-DEM) scenes are 3D (set dimension = 3): the "
                "DEM is 3D");
        }
      return run_and_report<FluidScene<dim>>(parameters, comm);
    }

    template std::map<std::string, double>
    run_scene(const core::Parameters<2> &, const MPI_Comm);
    template std::map<std::string, double>
    run_scene(const core::Parameters<3> &, const MPI_Comm);
  } // namespace drivers
} // namespace softsand
