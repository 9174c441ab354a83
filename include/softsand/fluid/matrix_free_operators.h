#ifndef softsand_fluid_matrix_free_operators_h
#define softsand_fluid_matrix_free_operators_h

#include <deal.II/base/subscriptor.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <functional>
#include <memory>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * Coefficients of the velocity block at the quadrature points of every
     * cell batch of one MatrixFree object: the operator is
     *
     *   mu (grad u, grad v) + (beta u, v) + (rho (w . grad) u, v)
     *     + (rho (grad w) u, v),
     *
     * beta the zeroth-order coefficient (penalty, rho/dt, Temam term), w the
     * advecting velocity (Oseen/Picard) and grad w the Newton term. Empty
     * tables switch the convective terms off.
     */
    template <int dim, typename Number>
    struct VelocityCoefficients
    {
      using VA                               = VectorizedArray<Number>;
      Number                       viscosity = 1;
      /// Per cell batch factor of the viscosity (0 in pressure-region
      /// cells, which carry only the pressure term); empty = 1.
      AlignedVector<VA>            viscosity_scale;
      Table<2, VA>                 reaction;
      Table<2, Tensor<1, dim, VA>> advection;          // rho w
      Table<2, Tensor<2, dim, VA>> advection_gradient; // rho grad w
    };


    /**
     * The velocity block on one multigrid level, whatever its polynomial
     * degree: what the smoothers, the transfer and the coarse solver need.
     * Constrained rows act as the identity so that Chebyshev and CG see a
     * regular operator; vectors are zero there.
     */
    template <int dim, typename Number>
    class VelocityLevelOperator : public Subscriptor
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<Number>;
      using value_type = Number;

      virtual ~VelocityLevelOperator() = default;

      virtual void
      vmult(VectorType &dst, const VectorType &src) const = 0;
      void
      Tvmult(VectorType &dst, const VectorType &src) const
      {
        vmult(dst, src);
      }
      void
      vmult_add(VectorType &dst, const VectorType &src) const;
      void
      Tvmult_add(VectorType &dst, const VectorType &src) const
      {
        vmult_add(dst, src);
      }

      virtual void
      initialize_dof_vector(VectorType &vector) const = 0;
      /// 1 / diagonal, 1 on constrained rows (Jacobi in Chebyshev).
      virtual void
      compute_inverse_diagonal(VectorType &inverse_diagonal) const = 0;
      /// The assembled operator (coarse-grid AMG), computed once.
      virtual const TrilinosWrappers::SparseMatrix &
      get_system_matrix() const = 0;

      types::global_dof_index
      m() const;
      /// Only for the interface of PreconditionChebyshev, which asks for
      /// entries when given no diagonal; we always give one.
      Number
      el(const unsigned int, const unsigned int) const
      {
        AssertThrow(false, ExcNotImplemented());
        return 0;
      }
      types::global_dof_index
      n() const
      {
        return m();
      }

    protected:
      std::shared_ptr<const MatrixFree<dim, Number>> matrix_free;
      unsigned int                                   dof_index = 0;
    };


    /**
     * Matrix-free velocity block with FE_Q(@p degree)^dim elements and
     * degree + 1 Gauss points per direction.
     */
    template <int dim, int degree, typename Number>
    class VelocityOperator : public VelocityLevelOperator<dim, Number>
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<Number>;
      using Evaluation = FEEvaluation<dim, degree, degree + 1, dim, Number>;

      void
      reinit(std::shared_ptr<const MatrixFree<dim, Number>>           data,
             std::shared_ptr<const VelocityCoefficients<dim, Number>> coeff,
             const AffineConstraints<Number> &constraints,
             const unsigned int               dof_index,
             const unsigned int               quad_index);

      void
      vmult(VectorType &dst, const VectorType &src) const override;
      void
      initialize_dof_vector(VectorType &vector) const override;
      void
      compute_inverse_diagonal(VectorType &inverse_diagonal) const override;
      const TrilinosWrappers::SparseMatrix &
      get_system_matrix() const override;

      /// The force (tested with v) and the flux (tested with grad v) of the
      /// operator at point @p q of cell batch @p cell.
      DEAL_II_ALWAYS_INLINE inline void
      quadrature_terms(const unsigned int                             cell,
                       const unsigned int                             q,
                       const Tensor<1, dim, VectorizedArray<Number>> &value,
                       const Tensor<2, dim, VectorizedArray<Number>> &grad,
                       Tensor<1, dim, VectorizedArray<Number>>       &force,
                       Tensor<2, dim, VectorizedArray<Number>> &flux) const
      {
        const auto &c    = *coefficients;
        const auto  beta = c.reaction(cell, q);
        for (unsigned int d = 0; d < dim; ++d)
          force[d] = beta * value[d];
        if (has_advection)
          {
            const auto &w = c.advection(cell, q);
            for (unsigned int d = 0; d < dim; ++d)
              for (unsigned int e = 0; e < dim; ++e)
                force[d] += grad[d][e] * w[e];
          }
        if (has_newton)
          {
            const auto &g = c.advection_gradient(cell, q);
            for (unsigned int d = 0; d < dim; ++d)
              for (unsigned int e = 0; e < dim; ++e)
                force[d] += g[d][e] * value[e];
          }
        const VectorizedArray<Number> mu =
          c.viscosity_scale.empty() ? VectorizedArray<Number>(c.viscosity) :
                                      c.viscosity * c.viscosity_scale[cell];
        for (unsigned int d = 0; d < dim; ++d)
          for (unsigned int e = 0; e < dim; ++e)
            flux[d][e] = mu * grad[d][e];
      }

      /// Apply the operator at the quadrature points (values and gradients
      /// already evaluated in @p phi).
      void
      do_quadrature(Evaluation &phi) const;

    private:
      void
      local_apply(const MatrixFree<dim, Number>               &data,
                  VectorType                                  &dst,
                  const VectorType                            &src,
                  const std::pair<unsigned int, unsigned int> &range) const;
      void
      local_compute(Evaluation &phi) const;

      std::shared_ptr<const VelocityCoefficients<dim, Number>> coefficients;
      bool has_advection = false, has_newton = false;
      const AffineConstraints<Number>       *constraints = nullptr;
      unsigned int                           quad_index  = 0;
      std::vector<unsigned int>              constrained_local_dofs;
      mutable TrilinosWrappers::SparseMatrix system_matrix;
    };


    /**
     * The Taylor-Hood Q2-Q1 saddle-point operator [A B^T; B 0] on a
     * MatrixFree object with the velocity (Q2^dim, dof index 0) and the
     * pressure (Q1, dof index 1) DoFHandlers, Gauss quadrature with 3 points
     * per direction. Signs as the matrix-based assembly:
     * B u = -(q, div u), B^T p = -(p, div v).
     */
    template <int dim>
    class StokesOperator : public Subscriptor
    {
    public:
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

      void
      reinit(std::shared_ptr<const MatrixFree<dim, double>>          data,
             std::shared_ptr<const VelocityOperator<dim, 2, double>> velocity,
             const AffineConstraints<double> &velocity_constraints,
             const AffineConstraints<double> &pressure_constraints,
             const TrilinosWrappers::SparseMatrix *pressure_block = nullptr);

      /// dst = K src; identity on constrained rows. K = [A B^T; B -C] with
      /// -C the assembled @p pressure_block of reinit() (rigid-node
      /// pressure smoothing; none if null).
      void
      vmult(BlockVectorType &dst, const BlockVectorType &src) const;
      /// dst -= K src with src read without constraints (its constrained
      /// entries hold the inhomogeneities): the lifting of the right-hand
      /// side. Constrained rows of dst are left alone.
      void
      subtract_plain(BlockVectorType &dst, const BlockVectorType &src) const;
      /// dst = B^T p (velocity rows of the pressure gradient).
      void
      apply_gradient(VectorType &dst, const VectorType &pressure) const;
      /// dst = B u (pressure rows of the divergence; constrained rows 0).
      void
      apply_divergence(VectorType &dst, const VectorType &velocity) const;

      /**
       * What one time step adds to the operator of a mesh (the transient
       * matrix-free path): cells with a nonzero entry of @p skip_cell (per
       * cell batch; their velocity nodes are all imposed, so they add
       * nothing to a free row) are left out of vmult(); the locally owned
       * rows @p step_velocity and @p step_pressure (local indices: the
       * grains' rigid nodes and pinned pressures, constrained in this step
       * only) act as identity rows; @p velocity_extra (assembled: the
       * traction faces' convective term) adds to the velocity block.
       * Vectors handed to vmult() must be zero on those rows.
       */
      void
      set_step_data(const std::vector<unsigned char>     *skip_cell,
                    const std::vector<unsigned int>      &step_velocity,
                    const std::vector<unsigned int>      &step_pressure,
                    const TrilinosWrappers::SparseMatrix *velocity_extra);
      /// dst = A src, the velocity block alone, with the rows and cells of
      /// set_step_data() (inner solves of the transient path).
      void
      vmult_velocity(VectorType &dst, const VectorType &src) const;
      /// Set the rows of set_step_data() and of the constraints to zero.
      void
      zero_constrained_rows(BlockVectorType &vector) const;
      void
      zero_constrained_velocity_rows(VectorType &vector) const;
      /// dst = src on the constrained pressure rows (identity rows).
      void
      copy_constrained_pressure_rows(VectorType       &dst,
                                     const VectorType &src) const;

      void
      initialize_dof_vector(BlockVectorType &vector) const;

    private:
      template <bool plain>
      void
      local_apply(const MatrixFree<dim, double>               &data,
                  BlockVectorType                             &dst,
                  const BlockVectorType                       &src,
                  const std::pair<unsigned int, unsigned int> &range) const;
      void
      local_gradient(const MatrixFree<dim, double>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &range) const;
      void
      local_divergence(
        const MatrixFree<dim, double>               &data,
        VectorType                                  &dst,
        const VectorType                            &src,
        const std::pair<unsigned int, unsigned int> &range) const;
      void
      local_velocity(const MatrixFree<dim, double>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &range) const;

      std::shared_ptr<const MatrixFree<dim, double>>          matrix_free;
      std::shared_ptr<const VelocityOperator<dim, 2, double>> velocity;
      std::vector<unsigned int> constrained_velocity, constrained_pressure;
      const TrilinosWrappers::SparseMatrix *pressure_block = nullptr;
      const TrilinosWrappers::SparseMatrix *velocity_extra = nullptr;
      const std::vector<unsigned char>     *skip_cell      = nullptr;
      std::vector<unsigned int> step_velocity, step_pressure;
      mutable VectorType                    pressure_tmp, velocity_tmp;
    };


    /**
     * Split the constraints @p combined of the combined Taylor-Hood handler
     * (velocity block first, @p n_velocity DoFs) by block, renumbered like
     * the separate handlers: @p velocity and @p pressure homogeneous, and,
     * if given, @p pressure_values the pressure ones with their values
     * (the lifting of assembled pressure blocks). All are reinitialized on
     * the relevant sets and closed.
     */
    void
    split_block_constraints(const AffineConstraints<double> &combined,
                            const types::global_dof_index    n_velocity,
                            const IndexSet &relevant_velocity,
                            const IndexSet &relevant_pressure,
                            AffineConstraints<double> &velocity,
                            AffineConstraints<double> &pressure,
                            AffineConstraints<double> *pressure_values);

    /// Locally owned rows (local indices) constrained in @p constraints.
    template <typename Number>
    std::vector<unsigned int>
    constrained_local_rows(const Utilities::MPI::Partitioner &partitioner,
                           const AffineConstraints<Number>   &constraints);
  } // namespace fluid
} // namespace softsand

#endif
