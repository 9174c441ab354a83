#ifndef softsand_drivers_convergence_study_h
#define softsand_drivers_convergence_study_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/convergence_table.h>
#include <softsand/core/parameters.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    /**
     * Runs a scene for each value of the knob (coarse to fine), each into
     * its own subdirectory of the output directory, and tabulates the
     * quantity of interest, its change against the finest run, the
     * observed order and Richardson estimate from consecutive triples,
     * cells, DoFs, FGMRES iterations, wall time and peak memory.
     */
    template <int dim>
    class ConvergenceStudy
    {
    public:
      /// One run of the study, in table order (coarse to fine).
      struct Run
      {
        double value = 0;
        /// Size of the knob: 1/N, 2^-refinements, 1/Theta or dt.
        double       h        = 0;
        double       quantity = 0;
        unsigned int cells    = 0;
        unsigned int dofs     = 0;
        /// FGMRES iterations summed over all solves of the run.
        unsigned int fgmres_iterations = 0;
        double       wall_time         = 0;
        /// CPU time (user + system) of the run, summed over ranks (s).
        double cpu_time = 0;
        /// Peak resident memory of the run, summed over ranks (MB).
        double peak_memory = 0;
        /// (Q - Q_finest) / |Q_finest|.
        double change_against_finest = 0;
        /// From this run and the two coarser ones; NaN where undefined
        /// (first two runs, a change of sign or a zero change).
        double observed_order = 0;
        /// Richardson estimate of the converged value and this run's
        /// relative distance from it; NaN where undefined.
        double richardson_estimate = 0;
        double richardson_error    = 0;
      };

      ConvergenceStudy(const core::Parameters<dim> &parameters, const MPI_Comm comm);

      void
      run();

      const std::vector<Run> &
      runs() const
      {
        return study_runs;
      }

      /// True if |Q - Q_finest| decreases from run to run.
      bool
      monotone() const;

      const ConvergenceTable &
      table() const
      {
        return convergence_table;
      }

    private:
      /// Stops for a scene the knob cannot vary.
      void
      check_scene() const;
      /// The scene's parameters with the knob at @p value, into the
      /// subdirectory run-@p k.
      core::Parameters<dim>
      parameters_of_run(const unsigned int k, const double value) const;
      /// Runs one scene; its quantity, size, iterations, time and memory.
      Run
      measure_run(const core::Parameters<dim> &run_parameters, const double value);
      void
      evaluate();
      void
      fill_table();
      /// Text, markdown and LaTeX tables (@p final: also to the screen).
      void
      write_tables(const bool final) const;

      const core::Parameters<dim> &parameters;
      MPI_Comm               mpi_communicator;
      ConditionalOStream     pcout;
      std::vector<Run>       study_runs;
      ConvergenceTable       convergence_table;
    };


    /// Observed order p of three values on knob sizes h_coarse > h_medium >
    /// h_fine (any ratios; Celik et al. 2008, fixed-point iteration), NaN
    /// if the changes vanish or alternate in sign.
    double
    observed_order(const double h_coarse,
                   const double h_medium,
                   const double h_fine,
                   const double q_coarse,
                   const double q_medium,
                   const double q_fine);
  } // namespace drivers
} // namespace softsand

#endif
