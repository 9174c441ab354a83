#ifndef softsand_drivers_fluid_scene_h
#define softsand_drivers_fluid_scene_h

#include <deal.II/base/timer.h>

#include <softsand/core/parameters.h>
#include <softsand/drivers/grain_resolved_fluid.h>
#include <softsand/drivers/scene_setup.h>
#include <softsand/io/statistics_file.h>

#include <map>
#include <memory>
#include <string>

namespace softsand
{
  namespace drivers
  {
    /**
     * The fluid on fixed grains (simulation control/mode = steady stokes,
     * steady navier stokes or transient): the box mesh refined around the
     * grains, then steady solves (with Kelly refinement cycles) or BDF time
     * steps, each followed by a statistics row.
     */
    template <int dim>
    class FluidScene
    {
    public:
      FluidScene(const core::Parameters<dim> &parameters, const MPI_Comm comm);

      void
      run();

      /// The last statistics row (name -> value).
      const std::map<std::string, double> &
      results() const
      {
        return last_results;
      }

    private:
      void
      solve_steady();
      void
      march_in_time();
      /// Refine the largest Kelly indicators of the velocity.
      void
      refine_by_velocity_error();
      void
      record(const unsigned int step, const double time, const bool write_fields);

      const core::Parameters<dim> &parameters;
      const MPI_Comm               mpi_communicator;
      SceneConsole                 console;
      TimerOutput                  timer;
      Timer                        wall_clock;
      GrainResolvedFluid<dim>      fluid;
      std::unique_ptr<io::StatisticsFile> statistics;
      std::map<std::string, double>       last_results;
    };
  } // namespace drivers
} // namespace softsand

#endif
