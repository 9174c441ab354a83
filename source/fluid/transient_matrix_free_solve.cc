// The transient matrix-free step's linear solve: D = diag(A) and the
// pressure matrix X = B D^-1 B^T + C with its AMG (the preconditioner
// set-up), then FGMRES with the block preconditioner of
// transient_block_preconditioner.h (Jacobi-GMRES on the velocity block,
// CG + AMG on X).

#include <deal.II/fe/fe_tools.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/lac/vector_memory.h>

#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/box_cell_tensors.h>
#include <softsand/fluid/transient_block_preconditioner.h>
#include <softsand/fluid/transient_matrix_free.h>

#include <algorithm>

namespace softsand
{
  namespace fluid
  {
    using namespace internal;

    template <int dim>
    void
    PenalizedNavierStokes<dim>::setup_matrix_free_preconditioner(
      const double       dt,
      const unsigned int order)
    {
      TransientMatrixFree           &data        = *transient_matrix_free;
      const MatrixFree<dim, double> &matrix_free = *data.matrix_free;
      const auto &partitioner_u = *matrix_free.get_vector_partitioner(0);
      const unsigned int owned_u   = partitioner_u.locally_owned_size();
      const unsigned int n_batches = matrix_free.n_cell_batches();
      const double       mu        = fluid_parameters.viscosity;
      constexpr unsigned int n_q   = Utilities::pow(3, dim);
      TimerOutput::Scope t(timer, "fluid: preconditioner setup");
      // D = diag(A) from each cell's mass and Laplacian diagonals with the
      // cell's mean coefficients (1 on imposed rows), and the pressure
      // matrix X = B D^-1 B^T + C of the least-squares commutator with
      // the mesh's B (an element-by-element X, sum_K B_K D^-1 B_K^T, cost
      // 40-80 FGMRES iterations instead of 10-14: doc/notes/solver_study.md).
      matrix_free.initialize_dof_vector(data.inverse_diagonal, 0);
      const auto &coefficients = *data.coefficients;
      std::vector<types::global_dof_index> u_dofs(
        fe_velocity.n_dofs_per_cell());
      const std::vector<unsigned int> h2l =
        FETools::hierarchic_to_lexicographic_numbering<dim>(2);
      LocalTensors<dim>        tensors;
      LocalTensorComputer<dim> tensor_computer;
      for (unsigned int batch = 0; batch < n_batches; ++batch)
        for (unsigned int lane = 0;
             lane < matrix_free.n_active_entries_per_cell_batch(batch);
             ++lane)
          {
            if (data.skip[batch])
              continue;
            const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
            double     beta = 0;
            for (unsigned int q = 0; q < n_q; ++q)
              beta += coefficients.reaction(batch, q)[lane];
            beta /= n_q;
            const double viscosity =
              mu * coefficients.viscosity_scale[batch][lane];
            tensor_computer.compute(cell, tensors);
            cell->get_dof_indices(u_dofs);
            for (unsigned int i = 0; i < u_dofs.size(); ++i)
              {
                const unsigned int l =
                  h2l[fe_velocity.system_to_component_index(i).second];
                data.inverse_diagonal.local_element(
                  partitioner_u.global_to_local(u_dofs[i])) +=
                  beta * tensors.mass[l] + viscosity * tensors.stiffness[l];
              }
          }
      data.inverse_diagonal.compress(VectorOperation::add);
      // X takes 1 / D of every node that is not imposed: B^T's rows are
      // scaled in place from its values as assembled.
      {
        std::vector<bool> step_row(owned_u, false);
        for (const auto i : data.step_velocity)
          step_row[i] = true;
        Epetra_CrsMatrix &gradient =
          const_cast<Epetra_CrsMatrix &>(data.gradient.trilinos_matrix());
        std::size_t k = 0;
        for (int row = 0; row < gradient.NumMyRows(); ++row)
          {
            const unsigned int i = partitioner_u.global_to_local(
              TrilinosWrappers::global_row_index(gradient, row));
            const double d = data.inverse_diagonal.local_element(i);
            const double weight =
              (step_row[i] || (data.velocity_flags[i] & 1) ||
               !(std::abs(d) > 0)) ?
                0. :
                1. / d;
            int     n_entries;
            double *values;
            int    *columns;
            gradient.ExtractMyRowView(row, n_entries, values, columns);
            for (int e = 0; e < n_entries; ++e, ++k)
              values[e] = weight * data.gradient_values[k];
          }
      }
      {
        std::vector<bool> unit(owned_u, false);
        for (const auto &line : data.velocity_constraints.get_lines())
          if (partitioner_u.in_local_range(line.index))
            unit[partitioner_u.global_to_local(line.index)] = true;
        for (unsigned int i = 0; i < owned_u; ++i)
          {
            double &d = data.inverse_diagonal.local_element(i);
            d         = (unit[i] || (data.velocity_flags[i] & 1) ||
                 !(std::abs(d) > 0)) ?
                          1. :
                          1. / d;
          }
        for (const auto i : data.step_velocity)
          data.inverse_diagonal.local_element(i) = 1.;
      }
      data.inverse_diagonal.update_ghost_values();

      // X is formed every step (kept from the last step, it doubled the
      // FGMRES iterations on the small Hele-Shaw scene); its AMG is kept
      // over steps of the same length and order (a preconditioner of
      // the inner CG) until that CG needs twice the iterations it took
      // when the AMG was built.
      data.rebuilt_schur = data.schur.m() == 0 || dt != data.schur_time_step ||
                      order != data.schur_order ||
                      data.last_iterations >
                        2 * data.schur_reference_iterations + 1;
      {
          data.schur_time_step = dt;
          data.schur_order     = order;
          const TrilinosWrappers::SparseMatrix *smoothing =
            data.has_smoothing ? &data.smoothing : nullptr;
          if (!data.schur_product.initialized())
            data.schur_product.initialize(data.divergence,
                                          data.gradient,
                                          smoothing,
                                          data.schur);
          else
            data.schur_product.refresh(data.divergence,
                                       data.gradient,
                                       smoothing,
                                       data.schur);
          TrilinosWrappers::PreconditionAMG::AdditionalData amg;
          amg.elliptic              = true;
          amg.higher_order_elements = false;
          amg.smoother_sweeps       = 2;
          amg.aggregation_threshold = 0.02;
          if (data.rebuilt_schur)
            {
              // ML keeps a reference to its matrix: a copy of X of this
              // step, which the next steps' X does not replace.
              data.schur_amg.clear();
              data.schur_of_amg.copy_from(data.schur);
              data.schur_amg.initialize(data.schur_of_amg, amg);
            }
        }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::solve_matrix_free_step()
    {
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;
      TransientMatrixFree           &data        = *transient_matrix_free;
      const MatrixFree<dim, double> &matrix_free = *data.matrix_free;
      const auto &partitioner_u = *matrix_free.get_vector_partitioner(0);
      const auto &partitioner_p = *matrix_free.get_vector_partitioner(1);
      const unsigned int owned_u = partitioner_u.locally_owned_size();
      const unsigned int owned_p = partitioner_p.locally_owned_size();
      BlockVectorType &rhs = data.rhs, &lifting = data.lifting;
      TimerOutput::Scope t(timer, "fluid: solve");
      // Start from the previous state (correction form, zero on every
      // constrained row).
      BlockVectorType delta;
      delta.reinit(2);
      data.copy_to_kernel_layout(solution, 0, delta.block(0));
      data.copy_to_kernel_layout(solution, 1, delta.block(1));
      delta.collect_sizes();
      data.stokes.zero_constrained_rows(delta);
      const double  rhs_norm = rhs.l2_norm();
      SolverControl control(
        solver_parameters.max_linear_iterations,
        std::max(solver_parameters.linear_tolerance * rhs_norm, 1e-300),
        false,
        false);
      // The velocity block's inner solve: a loose Jacobi-GMRES (FGMRES is
      // flexible; tighter inner solves cost more than the outer iterations
      // they save, doc/notes/solver_study.md).
      const TransientBlockPreconditioner<dim> preconditioner(
        data.stokes,
        data.inverse_diagonal,
        data.schur,
        data.schur_amg,
        velocity_inner_reduction,
        velocity_inner_iterations);
      SolverFGMRES<BlockVectorType> solver(
        control,
        typename SolverFGMRES<BlockVectorType>::AdditionalData(
          solver_parameters.krylov_restart));
      try
        {
          if (rhs_norm > 0)
            solver.solve(data.stokes, delta, rhs, preconditioner);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          AssertThrow(false,
                      ExcMessage(linear_solver_failure(e, control.tolerance())));
        }
      const unsigned int iterations = rhs_norm > 0 ? control.last_step() : 0;
      data.last_iterations =
        preconditioner.schur_cg_iterations /
        std::max(preconditioner.inner_solves, 1u);
      if (data.rebuilt_schur)
        data.schur_reference_iterations = data.last_iterations;
      if (preconditioner.inner_solves > 0)
        pcout << "      matrix-free step: " << iterations
              << " FGMRES iterations, velocity GMRES "
              << preconditioner.inner_iterations / preconditioner.inner_solves
              << " per application, X CG "
              << preconditioner.schur_cg_iterations / preconditioner.inner_solves
              << (data.rebuilt_schur ? " (AMG rebuilt)" : "") << ", "
              << matrix_free.n_cell_batches() << " cell batches, "
              << std::count(data.skip.begin(), data.skip.end(), 1)
              << " skipped" << std::endl;

      BlockVector x(owned_partitioning, mpi_communicator);
      for (unsigned int i = 0; i < owned_u; ++i)
        x.block(0)(partitioner_u.local_to_global(i)) =
          delta.block(0).local_element(i);
      for (unsigned int i = 0; i < owned_p; ++i)
        x.block(1)(partitioner_p.local_to_global(i)) =
          delta.block(1).local_element(i);
      x.compress(VectorOperation::insert);
      accept_linear_solution(x, iterations);
      rhs.reinit(0);
      lifting.reinit(0);
      delta.reinit(0);
      // The Krylov bases stay in deal.II's vector pools after a solve (two
      // block vectors per FGMRES iteration, 350 B per DoF at 22
      // iterations): give them back, or they sit beside the next step's X
      // and its product, the step's peak (doc/notes/solver_study.md).
      GrowingVectorMemory<BlockVectorType>::release_unused_memory();
      GrowingVectorMemory<VectorType>::release_unused_memory();
    }


    template void
    PenalizedNavierStokes<2>::setup_matrix_free_preconditioner(const double, const unsigned int);
    template void
    PenalizedNavierStokes<3>::setup_matrix_free_preconditioner(const double, const unsigned int);
    template void
    PenalizedNavierStokes<2>::solve_matrix_free_step();
    template void
    PenalizedNavierStokes<3>::solve_matrix_free_step();
  } // namespace fluid
} // namespace softsand
