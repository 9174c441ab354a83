#ifndef softsand_fluid_block_schur_preconditioner_h
#define softsand_fluid_block_schur_preconditioner_h

#include <deal.II/base/subscriptor.h>

#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <softsand/fluid/discrete_brinkman_solver.h>
#include <softsand/fluid/fluid_parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /// AMG settings of the pressure Laplacian of the Schur approximation
    /// (shared by the matrix-based and the matrix-free solves).
    TrilinosWrappers::PreconditionAMG::AdditionalData
    pressure_laplace_amg_data();

    /// X = @p product - @p c, made regular: product = B D^-1 B^T and c the
    /// pressure block -C of [A B^T; B -C] (rigid-node smoothing; the
    /// positive constraint diagonal on constrained rows), or none if null.
    void
    discrete_brinkman_from_product(const TrilinosWrappers::SparseMatrix &product,
                                   const TrilinosWrappers::SparseMatrix *c,
                                   TrilinosWrappers::SparseMatrix       &x);

    /**
     * X = B G - C of discrete_brinkman_from_product() (G = D^-1 B^T), formed
     * again at every step on the patterns of the mesh's first: EpetraExt's
     * product into a matrix of the product's own pattern builds no graph,
     * and X's values are summed through column maps kept per mesh (the
     * general product's new graph and copies were most of the transient
     * step's preconditioner set-up).
     */
    class DiscreteBrinkmanProduct
    {
    public:
      /// Whether initialize() has given the patterns.
      bool
      initialized() const;

      /// The mesh's first X (its pattern, and the product's).
      void
      initialize(const TrilinosWrappers::SparseMatrix &divergence,
                 const TrilinosWrappers::SparseMatrix &gradient,
                 const TrilinosWrappers::SparseMatrix *c,
                 TrilinosWrappers::SparseMatrix       &x);

      /// X's values again, for matrices of the patterns initialize() saw.
      void
      refresh(const TrilinosWrappers::SparseMatrix &divergence,
              const TrilinosWrappers::SparseMatrix &gradient,
              const TrilinosWrappers::SparseMatrix *c,
              TrilinosWrappers::SparseMatrix       &x);

    private:
      TrilinosWrappers::SparseMatrix product;
      /// The product's and C's local columns as X's.
      std::vector<int> product_columns, c_columns;
      /// False where some rank owns no row (refresh() forms X anew).
      bool every_rank_has_rows = true;
    };

    /**
     * Block upper-triangular preconditioner for the saddle-point system
     * [A B^T; B 0] of the penalized Navier-Stokes equations, applied inside
     * FGMRES: one AMG V-cycle for the velocity block A and, for the Schur
     * complement S = B A^-1 B^T,
     *
     *   S^-1 ~ M_(1/mu)^-1 + L_(1/beta)^-1,
     *
     * the Cahouet-Chabard sum generalised to a variable zeroth-order
     * coefficient beta (mass/dt in fluid, the penalty inside grains): where
     * beta dominates, A ~ beta M and S ~ -div((1/beta) grad), a Laplacian,
     * not a mass matrix. M is applied by ILU(0), L by one AMG V-cycle. Without
     * the Laplacian it is the plain (or weighted) pressure-mass
     * preconditioner.
     *
     * schur = discrete brinkman: L is instead the discrete
     * X = B D^-1 B^T + C with D = diag(A) (viscous + penalty + inertia; a
     * sparse triple product) and C the pressure block (rigid-node pressure
     * smoothing), inverted by DiscreteBrinkmanSolver (direct or CG + AMG). In
     * a dense pack the continuous L_(1/beta), weighted per quadrature
     * point, lets pressure "flow" through cut cells that the assembled A
     * closes: FGMRES needed 2,453 iterations on a 13-grain piece of the
     * Fig. 3 pack, 92 with this (doc/validation.md). One AMG V-cycle on X
     * is not enough there (1,768): the contrast of D (1e11) needs the inner
     * CG.
     *
     * schur = least squares commutator: S^-1 ~ X^-1 (B D^-1 A D^-1 B^T +
     * C) X^-1 (Elman et al.'s diagonally scaled BFBT, with the pressure
     * block in the middle as in their stabilized variant; no pressure mass
     * matrix).
     * Where the penalty dominates, A ~ D and it reduces to X^-1; in the
     * fluid it is the commutator approximation, which also contains the
     * convection of an Oseen block. Two inner CG solves per application.
     */

    class BlockSchurPreconditioner : public Subscriptor
    {
    public:
      using BlockVector = TrilinosWrappers::MPI::BlockVector;

      /// @p velocity_smoother is the ML smoother of the velocity AMG:
      /// Chebyshev assumes a symmetric positive block; the convective
      /// (Newton/Picard) block of steady flow needs "symmetric Gauss-Seidel".
      /// @p smoothed_aggregation: ML's smoothed prolongators instead of
      /// plain aggregates for that AMG.
      BlockSchurPreconditioner(
        const TrilinosWrappers::BlockSparseMatrix &system_matrix,
        const TrilinosWrappers::BlockSparseMatrix &pressure_mass_matrix,
        const TrilinosWrappers::BlockSparseMatrix *pressure_laplace_matrix,
        const std::vector<std::vector<bool>>      &velocity_constant_modes,
        const unsigned int                         amg_sweeps,
        const std::string           &velocity_smoother = "Chebyshev",
        const SolverParameters::Schur schur = SolverParameters::Schur::mass,
        const double                 inner_tolerance = 1e-6,
        const bool                   direct_velocity_solve = false,
        const SolverParameters::SchurInnerSolver inner_solver =
          SolverParameters::SchurInnerSolver::direct,
        const bool smoothed_aggregation = false);

      void
      vmult(BlockVector &dst, const BlockVector &src) const;

    private:
      const TrilinosWrappers::BlockSparseMatrix &system_matrix;
      /// ML keeps a pointer to the smoother name: it must outlive the AMG.
      const std::string                          velocity_smoother;
      TrilinosWrappers::PreconditionAMG          velocity_amg;
      /// A sparse direct factorization of the velocity block instead of
      /// the AMG V-cycle (small problems; diagnosis of convective blocks).
      SolverControl                              direct_control;
      std::unique_ptr<TrilinosWrappers::SolverDirect> velocity_direct;
      TrilinosWrappers::PreconditionILU          pressure_mass_ilu;
      TrilinosWrappers::PreconditionAMG          pressure_laplace_amg;
      const SolverParameters::Schur              schur;
      bool                                       use_laplace;
      /// X = B diag(A)^-1 B^T + C (discrete brinkman, least squares
      /// commutator; else empty).
      TrilinosWrappers::SparseMatrix             discrete_brinkman;
      /// diag(A)^-1 (least squares commutator).
      TrilinosWrappers::MPI::Vector              inverse_velocity_diagonal;
      DiscreteBrinkmanSolver                     discrete_brinkman_inverse;
      mutable TrilinosWrappers::MPI::Vector      tmp_u, tmp_u2, tmp_p, tmp_p2;
    };
  } // namespace fluid
} // namespace softsand

#endif
