#ifndef softsand_drivers_coupled_scene_h
#define softsand_drivers_coupled_scene_h

#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <softsand/core/parameters.h>
#include <softsand/coupling/held_force_model.h>
#include <softsand/dem/granular_dynamics.h>
#include <softsand/drivers/grain_resolved_fluid.h>
#include <softsand/drivers/scene_setup.h>
#include <softsand/io/grain_output.h>
#include <softsand/io/statistics_file.h>
#include <softsand/postprocess/columns/grain_columns.h>
#include <softsand/postprocess/fracture_development.h>

#include <map>
#include <memory>
#include <string>
#include <utility>

namespace softsand
{
  namespace drivers
  {
    /**
     * The coupled CFD-DEM scene (simulation control/mode = coupled; 3D):
     * the DEM's grains seen by the penalized fluid, the fluid forces held
     * over the DEM sub-steps, the fluid mesh following the grains. One
     * coupling step is the short list of named steps in run()
     * (doc/architecture.md, "One coupled step").
     */
    class CoupledScene
    {
    public:
      CoupledScene(const core::Parameters<3> &parameters, const MPI_Comm comm);

      void
      run();

      /// The fluid columns of the last row and the final grain state.
      const std::map<std::string, double> &
      results() const
      {
        return last_results;
      }

    private:
      /// The DEM, the fluid mesh and solver, or the state of a checkpoint.
      void
      set_up();
      /// The coupling step: the scene's, shortened in the quasi-steady
      /// model so that no grain moves more than a fraction of a cell and
      /// the held drag does not outlast the grains' response time, and in
      /// the transient model halved to 'max courant number'.
      double
      choose_time_step();
      /// Warn once when a fixed transient step runs at a Courant number
      /// where the Oseen solve degrades.
      void
      warn_about_courant_number() const;
      /// Re-adapt the fluid mesh once a grain moved a fraction of a cell.
      void
      follow_grains();
      /// Whether the injection's fracture has developed (the stops of
      /// postprocessing/fracture area): then this step is the last.
      void
      judge_fracture_development();
      void
      solve_fluid(const double dt);
      void
      record_fluid(const double time, const bool write_fields);
      /// The fluid force and torque per grain id, held over the sub-steps.
      void
      hand_forces_to_grains(const double dt);
      void
      advance_grains(const double dt);
      /// The grains of the DEM (all ranks) into the fluid.
      void
      update_grains_from_dem();
      /// The grains' columns and the row to the file; stops on divergence.
      void
      record_grains(const double dt);
      /// Warns when the coupling step exceeds the grains' response time.
      void
      warn_about_response_time() const;
      /// Penalization with more than one grain: warn where the penalty
      /// coupling number exceeds what the coupled step was measured stable at.
      void
      warn_about_penalty_coupling() const;
      void
      report_progress(const bool last, const Timer &loop_clock);
      void
      finish();

      /// In coupled_checkpoint.cc.
      void
      write_checkpoint();

      /// A stop signal (base::install_stop_handlers) after this step: write
      /// a checkpoint unless @p checkpointed already, and say so.
      bool
      stop_on_request(const bool checkpointed);
      void
      read_checkpoint();

      const core::Parameters<3> &parameters;
      const MPI_Comm             mpi_communicator;
      SceneConsole               console;
      TimerOutput                timer;
      Timer                      wall_clock;
      const BoundingBox<3>       box;

      GrainResolvedFluid<3> fluid;
      // The DEM on its own coarse mesh (cells at least one contact range
      // wide, so that its ghost layer is the contact halo), and the grain
      // ids behind fluid.grains().
      std::unique_ptr<parallel::distributed::Triangulation<3>> dem_triangulation;
      std::unique_ptr<dem::GranularDynamics>                   dem;
      std::vector<types::particle_index>                       grain_ids;
      std::unique_ptr<coupling::HeldForceModel>                held_force;
      postprocess::GrainColumns                                grain_columns;

      std::unique_ptr<io::StatisticsFile> statistics;
      std::unique_ptr<io::GrainOutput>    grain_output;
      std::map<std::string, double>       last_results;
      std::unique_ptr<postprocess::FractureDevelopment> fracture_development;
      /// Why the fracture counts as developed (empty: not yet).
      std::string developed_fracture;
      /// Why the time loop ended, for the end-of-run summary.
      std::string end_reason = "the end time or step count was reached";

      unsigned int step               = 0;
      double       time               = 0;
      unsigned int n_mesh_adaptations = 0;
      /// The finest fluid cell at the start (m).
      double finest_cell = 0;
      /// The grains' shortest response time (s).
      double response_time = 0;
      /// Transient model: the largest cell Courant number of this step
      /// (from the last fluid solution; -1: quasi-steady).
      double courant_number = -1;
      /// Loop wall time of the last progress line (s).
      double last_report = -1e300;
      /// The step and time this process's loop started from (0, or a
      /// checkpoint's).
      unsigned int first_step = 0;
      double       start_time = 0;
    };
  } // namespace drivers
} // namespace softsand

#endif
