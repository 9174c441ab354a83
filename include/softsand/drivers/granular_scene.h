#ifndef softsand_drivers_granular_scene_h
#define softsand_drivers_granular_scene_h

#include <deal.II/distributed/tria.h>

#include <deal.II/base/timer.h>

#include <softsand/core/parameters.h>
#include <softsand/dem/granular_dynamics.h>
#include <softsand/drivers/scene_setup.h>
#include <softsand/io/grain_output.h>
#include <softsand/io/statistics_file.h>
#include <softsand/io/wall_output.h>
#include <softsand/postprocess/columns/grain_columns.h>

#include <map>
#include <memory>
#include <string>

namespace softsand
{
  namespace drivers
  {
    /**
     * A scene of grains alone (simulation control/mode = granular): insert
     * or load a pack, then move it under contacts, walls and gravity until
     * the end time or until it has settled. No fluid system is built. The
     * mesh is only the grains' home for parallel distribution: cells at
     * least one contact range (2 r_max + skin) wide.
     */
    class GranularScene
    {
    public:
      GranularScene(const core::Parameters<3> &parameters, const MPI_Comm comm);

      void
      run();

      /// Final numbers (name -> value), as printed by the run.
      const std::map<std::string, double> &
      results() const
      {
        return last_results;
      }

      const dem::GranularDynamics &
      dynamics() const
      {
        return *dem;
      }

    private:
      /// The grains, their mesh, the DEM and the output files.
      void
      set_up();
      /// The end time or the step limit reached (the step may adapt: the
      /// time nearest to the end time).
      bool
      finished() const;
      /// A statistics row.
      void
      record();
      void
      write_grains();
      /// Settled: little motion and every servo wall at its target, for
      /// dem/settled checks rows in a row.
      bool
      check_settled();
      void
      report_progress();
      /// The pack file's note (and a warning) for a pack saved unsettled.
      std::string
      unsettled_note() const;
      void
      finish(const bool last_recorded);
      /// checkpoint-STEP.dem and checkpoint.info (checkpoint_files.h).
      void
      write_checkpoint();
      /// The state of the checkpoint in the output directory.
      void
      read_checkpoint();

      const core::Parameters<3>              &parameters;
      const MPI_Comm                          mpi_communicator;
      SceneConsole                            console;
      Timer                                   wall_clock;
      Timer                                   loop_clock;
      const BoundingBox<3>                    box;
      const postprocess::GrainColumns         grain_columns;
      parallel::distributed::Triangulation<3> triangulation;
      std::unique_ptr<dem::GranularDynamics>  dem;
      std::unique_ptr<io::StatisticsFile>     statistics;
      std::unique_ptr<io::GrainOutput>        grain_output;
      std::unique_ptr<io::WallOutput>         wall_output;
      std::map<std::string, double>           last_results;

      /// The last row's statistics.
      dem::GranularStatistics last_statistics;
      unsigned int            settled_rows    = 0;
      /// The largest servo error over the settled rows.
      double                  max_servo_error = 0;
      bool                    settled         = false;
      double                  next_report     = 10;
      /// The DEM step and time this run started from (0, or a
      /// checkpoint's).
      unsigned long           first_step      = 0;
      double                  start_time      = 0;
    };
  } // namespace drivers
} // namespace softsand

#endif
