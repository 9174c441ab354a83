#ifndef softsand_fluid_discrete_brinkman_solver_h
#define softsand_fluid_discrete_brinkman_solver_h

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <softsand/fluid/fluid_parameters.h>

#include <memory>

class Amesos_BaseSolver;
class Epetra_LinearProblem;

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * The inner solves of the discrete-Brinkman and least-squares-commutator
     * Schur approximations: X y = r with X = B D^-1 B^T + C, a pressure
     * matrix whose coefficient D^-1 jumps by the penalty contrast (1e6-1e11)
     * at every grain surface and which dense packs split into pores joined
     * only through that contrast.
     *
     * Two methods:
     * - direct: a sparse LU factorization (MUMPS through Amesos, PORD
     *   ordering), made once per preconditioner setup;
     *   each solve is then exact, whatever the contrast and the pockets.
     *   It costs memory and time that grow faster than the pressure unknowns
     *   (about n^(4/3) and n^2 in 3D), so it suits the scenes' pressure
     *   spaces (1e4-1e6 unknowns: the velocity has 25x more).
     * - amg cg: CG preconditioned by an ML AMG V-cycle to a relative
     *   tolerance, stopped at 200 iterations (an inexact solve that stops
     *   at its bound still returns its last iterate: FGMRES). Memory linear
     *   in the unknowns, but on penalized packs the iteration count reaches
     *   its bound (doc/notes/solver_study.md).
     */
    class DiscreteBrinkmanSolver
    {
    public:
      using Method = SolverParameters::SchurInnerSolver;

      DiscreteBrinkmanSolver();
      ~DiscreteBrinkmanSolver();

      /// Factorize (direct) or build the AMG (amg cg) of @p x, which must
      /// outlive this object's use. direct: when the pressure level is free
      /// (no pressure face: X 1 = 0), one diagonal entry of @p x is doubled
      /// first, see pin_pressure_level().
      void
      initialize(TrilinosWrappers::SparseMatrix &x,
                 const Method                          method,
                 const double                          inner_tolerance);

      void
      clear();

      bool
      empty() const
      {
        return matrix == nullptr;
      }

      /// Whether X is factorized (direct, not fallen back to amg cg): each
      /// solve is then the same linear operator.
      bool
      is_exact() const
      {
        return method == Method::direct;
      }

      void
      solve(TrilinosWrappers::MPI::Vector       &dst,
            const TrilinosWrappers::MPI::Vector &src) const;

      void
      solve(LinearAlgebra::distributed::Vector<double>       &dst,
            const LinearAlgebra::distributed::Vector<double> &src) const;

      /// Solves so far, their inner CG iterations (0 for direct) and their
      /// wall time (s).
      mutable unsigned int solves = 0, iterations = 0;
      mutable double       wall_time = 0;

    private:
      const TrilinosWrappers::SparseMatrix   *matrix = nullptr;
      Method                                  method = Method::amg_cg;
      double                                  tolerance = 1e-6;
      TrilinosWrappers::PreconditionAMG       amg;
      std::unique_ptr<Epetra_LinearProblem>   problem;
      std::unique_ptr<Amesos_BaseSolver>      factorization;

      /// Where X 1 = 0 on its coupled rows (no pressure face fixes the
      /// pressure level), one coupled diagonal entry X_kk is doubled. For
      /// every consistent right side (1^T r = 0) the pinned system's
      /// solution solves X y = r with y_k = 0, and LU no longer meets a
      /// zero pivot.
      static void
      pin_pressure_level(TrilinosWrappers::SparseMatrix &x);

      /// dst = X^-1 src on the locally owned entries (direct).
      void
      solve_direct(double *dst, const double *src) const;

      /// dst = X^-1 src by CG + AMG (amg cg), counted.
      template <typename VectorType>
      void
      solve_by_amg_cg(VectorType &dst, const VectorType &src) const;
    };
  } // namespace fluid
} // namespace softsand

#endif
