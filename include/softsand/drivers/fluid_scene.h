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
      /// checkpoint-STEP.fluid* and checkpoint.info (checkpoint_files.h).
      void
      write_checkpoint(const unsigned int step, const double time);
      /// A restart: the mesh of the checkpoint in the output directory.
      void
      load_checkpoint_mesh();
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
      /// Where a restarted transient run resumes: step, time and BDF steps
      /// of its checkpoint.
      unsigned int first_step       = 0;
      double       first_time       = 0;
      unsigned int first_steps_done = 0;
      std::map<std::string, double>       last_results;
    };
  } // namespace drivers
} // namespace softsand

#endif
