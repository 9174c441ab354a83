#ifndef softsand_fluid_velocity_multigrid_h
#define softsand_fluid_velocity_multigrid_h

#include <deal.II/base/mg_level_object.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include <softsand/fluid/matrix_free_operators.h>

#include <functional>
#include <memory>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * One V-cycle of geometric multigrid for the velocity block
     * mu (grad u, grad v) + (beta u, v) (+ convection), the preconditioner of
     * the matrix-free Stokes solver. The levels are the Q2 operator on the
     * active mesh, Q1 on the same mesh, then Q1 on the meshes obtained by
     * coarsening every cell once per level (global coarsening, so the
     * adaptive p4est mesh needs no level hierarchy); Chebyshev smoothing
     * around point Jacobi, and a CG solve with AMG on the coarsest mesh.
     * Coarser levels see the grains by rediscretization: the caller's
     * functions give each level its constraints and its coefficient beta.
     */
    template <int dim>
    class VelocityMultigrid : public Subscriptor
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      struct Settings
      {
        unsigned int smoother_degree       = 4;
        double       smoothing_range       = 20;
        unsigned int eigenvalue_iterations = 20;
        double       coarse_tolerance      = 1e-3;
        /// Geometric levels below Q1 on the active mesh (true), or none:
        /// the coarse problem is Q1 on the active mesh, solved by AMG on
        /// its assembled matrix (p-multigrid with an algebraic coarse
        /// solver; it sees the grains as the fine mesh does).
        bool         geometric_levels      = true;
      };

      /// Homogeneous constraints of a level: boundary, hanging and solid.
      using ConstraintFunction =
        std::function<void(const DoFHandler<dim> &,
                           AffineConstraints<double> &)>;
      /// The zeroth-order coefficient beta at the points of a cell; the
      /// flag says whether the cell belongs to the active (finest) mesh.
      using CoefficientFunction =
        std::function<void(const CellAccessor<dim, dim> &,
                           const std::vector<Point<dim>> &,
                           const bool,
                           std::vector<double> &)>;

      /**
       * Build the hierarchy below the fine (Q2) operator @p fine_operator,
       * which works on @p fine_dof_handler with @p fine_constraints.
       */
      void
      initialize(
        const DoFHandler<dim>           &fine_dof_handler,
        const AffineConstraints<double> &fine_constraints,
        std::shared_ptr<const VelocityLevelOperator<dim, double>> fine_operator,
        const ConstraintFunction  &make_constraints,
        const CoefficientFunction &coefficient,
        const double               viscosity,
        const Settings            &settings);

      /// One V-cycle: dst ~ A^-1 src.
      void
      vmult(VectorType &dst, const VectorType &src) const;

      unsigned int
      n_levels() const
      {
        return operators.max_level() + 1;
      }
      /// Unknowns on each level, coarsest first.
      std::vector<types::global_dof_index>
      level_sizes() const;

    private:
      using LevelOperator = VelocityLevelOperator<dim, double>;
      using Smoother      = PreconditionChebyshev<LevelOperator,
                                             VectorType,
                                             DiagonalMatrix<VectorType>>;

      std::vector<std::shared_ptr<const Triangulation<dim>>> triangulations;
      std::unique_ptr<FESystem<dim>>                         fe_q1;
      MGLevelObject<std::unique_ptr<DoFHandler<dim>>>        dof_handlers;
      MGLevelObject<AffineConstraints<double>>               constraints;
      MGLevelObject<std::shared_ptr<const LevelOperator>>    operators;
      MGLevelObject<MGTwoLevelTransfer<dim, VectorType>>     transfers;
      std::unique_ptr<MGTransferGlobalCoarsening<dim, VectorType>> transfer;

      mg::Matrix<VectorType>                                      mg_matrix;
      MGSmootherPrecondition<LevelOperator, Smoother, VectorType> mg_smoother;
      TrilinosWrappers::PreconditionAMG                           coarse_amg;
      /// CG with AMG on the coarsest mesh to a modest reduction; the cycle
      /// goes on with the last iterate if CG stops early (FGMRES absorbs an
      /// inexact coarse solve).
      class CoarseSolver : public MGCoarseGridBase<VectorType>
      {
      public:
        CoarseSolver(const LevelOperator                     &matrix,
                     const TrilinosWrappers::PreconditionAMG &amg,
                     const double                             tolerance)
            : matrix(matrix)
            , amg(amg)
            , tolerance(tolerance)
        {}
        void
                             operator()(const unsigned int,
                   VectorType       &dst,
                   const VectorType &src) const override;
        mutable unsigned int n_calls = 0, n_iterations = 0;

      private:
        const LevelOperator                     &matrix;
        const TrilinosWrappers::PreconditionAMG &amg;
        const double                             tolerance;
      };
      std::unique_ptr<CoarseSolver>          mg_coarse;
      std::unique_ptr<Multigrid<VectorType>> multigrid;
      std::unique_ptr<
        PreconditionMG<dim,
                       VectorType,
                       MGTransferGlobalCoarsening<dim, VectorType>>>
        preconditioner;
    };
  } // namespace fluid
} // namespace softsand

#endif
