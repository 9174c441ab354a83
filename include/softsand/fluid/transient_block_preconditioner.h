// The block preconditioner of the transient matrix-free step.
#ifndef softsand_fluid_transient_block_preconditioner_h
#define softsand_fluid_transient_block_preconditioner_h

#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <softsand/fluid/matrix_free_operators.h>

namespace softsand
{
  namespace fluid
  {
    namespace internal
    {
      using namespace dealii;

      /// The velocity block's inner Jacobi-GMRES: relative reduction and
      /// iterations per application (measured against 1e-2 / 20 and
      /// 3e-1 / 4 on the small Hele-Shaw scene, doc/notes/solver_study.md).
      constexpr double       velocity_inner_reduction  = 1e-1;
      constexpr unsigned int velocity_inner_iterations = 8;
      /// The pressure matrix X's CG: relative reduction and iterations.
      constexpr double       schur_reduction  = 1e-2;
      constexpr unsigned int schur_iterations = 30;

      /**
       * Block upper-triangular preconditioner of the transient matrix-free
       * step: p = -X^-1 r_p (one AMG V-cycle on X = B D^-1 B^T + C), then u
       * from A u = r_u - B^T p by a few Jacobi-preconditioned GMRES
       * iterations (A is dominated by the BDF mass at the Courant numbers
       * of the injections).
       */
      template <int dim>
      class TransientBlockPreconditioner
      {
      public:
        using VectorType      = LinearAlgebra::distributed::Vector<double>;
        using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

        TransientBlockPreconditioner(
          const StokesOperator<dim>               &stokes,
          const VectorType                        &inverse_diagonal,
          const TrilinosWrappers::SparseMatrix    &schur,
          const TrilinosWrappers::PreconditionAMG &schur_amg,
          const double                             velocity_reduction,
          const unsigned int                       velocity_iterations)
          : stokes(stokes)
          , inverse_diagonal(inverse_diagonal)
          , schur(schur)
          , schur_amg(schur_amg)
          , velocity_reduction(velocity_reduction)
          , velocity_iterations(velocity_iterations)
        {}

        void
        vmult(BlockVectorType &dst, const BlockVectorType &src) const
        {
          // X^-1 by CG with the AMG: the V-cycle alone doubled the outer
          // iterations, and X has a 25th of the unknowns.
          dst.block(1) = 0;
          {
            ReductionControl control(schur_iterations,
                                     1e-300,
                                     schur_reduction,
                                     false,
                                     false);
            SolverCG<VectorType> cg(control);
            try
              {
                cg.solve(schur, dst.block(1), src.block(1), schur_amg);
              }
            catch (const SolverControl::NoConvergence &)
              {}
            schur_cg_iterations += control.last_step();
          }
          dst.block(1) *= -1.;
          tmp.reinit(src.block(0), true);
          stokes.apply_gradient(tmp, dst.block(1));
          tmp.sadd(-1., 1., src.block(0));
          stokes.zero_constrained_velocity_rows(tmp);
          dst.block(0) = 0;
          ReductionControl control(velocity_iterations,
                                   1e-300,
                                   velocity_reduction,
                                   false,
                                   false);
          SolverGMRES<VectorType> gmres(
            control,
            typename SolverGMRES<VectorType>::AdditionalData(
              velocity_iterations + 2));
          const VelocityBlock block{stokes};
          const Jacobi        jacobi{inverse_diagonal};
          try
            {
              gmres.solve(block, dst.block(0), tmp, jacobi);
            }
          catch (const SolverControl::NoConvergence &)
            {
              // An approximate inverse is all FGMRES needs.
            }
          inner_iterations += control.last_step();
          ++inner_solves;
          stokes.zero_constrained_rows(dst);
        }

        mutable unsigned int inner_iterations = 0, inner_solves = 0,
                             schur_cg_iterations = 0;

      private:
        struct VelocityBlock
        {
          const StokesOperator<dim> &stokes;
          void
          vmult(VectorType &dst, const VectorType &src) const
          {
            stokes.vmult_velocity(dst, src);
          }
        };
        struct Jacobi
        {
          const VectorType &inverse_diagonal;
          void
          vmult(VectorType &dst, const VectorType &src) const
          {
            dst = src;
            dst.scale(inverse_diagonal);
          }
        };

        const StokesOperator<dim>               &stokes;
        const VectorType                        &inverse_diagonal;
        const TrilinosWrappers::SparseMatrix    &schur;
        const TrilinosWrappers::PreconditionAMG &schur_amg;
        const double                             velocity_reduction;
        const unsigned int                       velocity_iterations;
        mutable VectorType                       tmp;
      };
    } // namespace internal
  }   // namespace fluid
} // namespace softsand

#endif
