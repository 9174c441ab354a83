#ifndef softsand_core_simulator_h
#define softsand_core_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <softsand/core/parameters.h>
#include <softsand/coupling/grain_solid_field.h>
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
      void
      make_mesh();
      void
      postprocess(const unsigned int step, const double time, const bool write_fields);
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
    };

    /// Read @p filename and run the scene in its dimension.
    void
    run_parameter_file(const std::string &filename, const MPI_Comm comm);
  } // namespace core
} // namespace softsand

#endif
