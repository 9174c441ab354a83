#ifndef softsand_core_simulator_h
#define softsand_core_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <softsand/core/parameters.h>
#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_solid_field.h>
#include <softsand/dem/granular_dynamics.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/io/field_output.h>
#include <softsand/io/statistics_file.h>

#include <map>
#include <memory>

namespace softsand
{
  namespace core
  {
    /**
     * Runs one scene: builds the box mesh and the grains, refines around the
     * grain surfaces, then solves the penalized fluid steadily or marches it
     * in time, with postprocessing and output after each solve. A scene with
     * fixed grains builds no DEM.
     */
    template <int dim>
    class Simulator
    {
    public:
      Simulator(const Parameters<dim> &parameters, const MPI_Comm comm);

      void
      run();

      /// Results of the last postprocessing (name -> value), as written to
      /// the statistics table; for tests and drivers.
      const std::map<std::string, double> &
      results() const
      {
        return last_results;
      }

      const fluid::PenalizedNavierStokes<dim> &
      fluid_solver() const
      {
        return *fluid;
      }

    private:
      /// The box mesh, refined around the grains unless @p refine is false
      /// (a restart loads the refinement).
      void
      make_mesh(const bool refine = true);
      /// Fluid results of the current state into the statistics row (and
      /// fields to files); with @p finish_row the row is written, else the
      /// caller adds to it first (the coupled loop adds the grains').
      void
      postprocess(const unsigned int step,
                  const double       time,
                  const bool         write_fields,
                  const bool         finish_row = true);

      /// Radial-cell (Hele-Shaw) columns into @p r: pressure rings, radial
      /// flow rate and permeability, fracture area (with a fracture map
      /// file when @p write_fields).
      void
      hele_shaw_diagnostics(std::map<std::string, double> &r,
                            const unsigned int             step,
                            const bool                     write_fields) const;

      /// The coupled CFD-DEM loop (mode = coupled; 3D).
      void
      run_coupled();
      /// Grains from the DEM (all ranks) and the solid field built on them.
      void
      update_grains_from_dem();
      /// Refine and coarsen the fluid mesh until it fits the grains, the
      /// fluid fields transferred (@p transfer) to the new mesh.
      unsigned int
      adapt_mesh_to_grains(const bool transfer);
      /// Largest grain displacement since the last mesh adaptation.
      double
      max_displacement_since_adaptation() const;
      void
      write_checkpoint(const unsigned int step, const double time);
      /// Returns the step and time of the checkpoint.
      std::pair<unsigned int, double>
      read_checkpoint();
      void
      print_results() const;

      const Parameters<dim> &parameters;
      MPI_Comm               mpi_communicator;
      ConditionalOStream     pcout;
      ConditionalOStream     progress;
      TimerOutput            timer;
      Timer                  wall_clock;

      parallel::distributed::Triangulation<dim>        triangulation;
      std::vector<dem::Grain<dim>>                     grains;
      std::unique_ptr<coupling::GrainSolidField<dim>>  solid_field;
      std::unique_ptr<fluid::PenalizedNavierStokes<dim>> fluid;
      std::unique_ptr<io::StatisticsFile>              statistics;
      std::map<std::string, double>                    last_results;
      std::unique_ptr<io::FieldOutput<dim>>            field_output;

      // Coupled runs only: the DEM on its own coarse mesh (cells at least
      // one contact range wide, so that its ghost layer is the contact
      // halo), the grain ids behind 'grains', where the grains were when
      // the fluid mesh was last adapted, and the last fluid forces.
      std::unique_ptr<parallel::distributed::Triangulation<3>> dem_triangulation;
      std::unique_ptr<dem::GranularDynamics>                   dem;
      std::vector<types::particle_index>                       grain_ids;
      std::vector<Point<dim>>                                  centers_at_adaptation;
      unsigned int                                             n_mesh_adaptations = 0;
      coupling::GrainForces<dim>                               grain_forces;
      coupling::GrainForces<dim>                               grain_forces_eq7;
      /// Per grain id at the last fluid solve: velocity, force, angular
      /// velocity, torque and the measured resistances (secants), so that
      /// the next step can linearize the held force; checkpointed.
      struct ResistanceHistory
      {
        std::vector<Tensor<1, 3>> velocity, force, angular_velocity, torque;
        std::vector<double>       resistance, rotational_resistance;
      } resistance_history;
    };

    /// Read @p filename and run the scene in its dimension.
    void
    run_parameter_file(const std::string &filename, const MPI_Comm comm);
  } // namespace core
} // namespace softsand

#endif
