#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/tools.h>

#include <softsand/fluid/matrix_free_operators.h>

namespace softsand
{
  namespace fluid
  {
    void
    split_block_constraints(const AffineConstraints<double> &combined,
                            const types::global_dof_index    n_velocity,
                            const IndexSet &relevant_velocity,
                            const IndexSet &relevant_pressure,
                            AffineConstraints<double> &velocity,
                            AffineConstraints<double> &pressure,
                            AffineConstraints<double> *pressure_values)
    {
      velocity.clear();
      velocity.reinit(relevant_velocity);
      pressure.clear();
      pressure.reinit(relevant_pressure);
      if (pressure_values != nullptr)
        {
          pressure_values->clear();
          pressure_values->reinit(relevant_pressure);
        }
      const auto copy_line = [n_velocity](const auto                &line,
                                          AffineConstraints<double> &c) {
        const bool velocity_line = line.index < n_velocity;
        const types::global_dof_index shift = velocity_line ? 0 : n_velocity;
        c.add_line(line.index - shift);
        for (const auto &[column, weight] : line.entries)
          {
            Assert((column < n_velocity) == velocity_line, ExcInternalError());
            c.add_entry(line.index - shift, column - shift, weight);
          }
      };
      for (const auto &line : combined.get_lines())
        if (line.index < n_velocity)
          copy_line(line, velocity);
        else
          {
            copy_line(line, pressure);
            if (pressure_values != nullptr)
              {
                copy_line(line, *pressure_values);
                pressure_values->set_inhomogeneity(line.index - n_velocity,
                                                   line.inhomogeneity);
              }
          }
      velocity.close();
      pressure.close();
      if (pressure_values != nullptr)
        pressure_values->close();
    }


    template <typename Number>
    std::vector<unsigned int>
    constrained_local_rows(const Utilities::MPI::Partitioner &partitioner,
                           const AffineConstraints<Number>   &constraints)
    {
      std::vector<unsigned int> rows;
      const IndexSet           &owned = partitioner.locally_owned_range();
      for (const auto &line : constraints.get_lines())
        if (owned.is_element(line.index))
          rows.push_back(partitioner.global_to_local(line.index));
      std::sort(rows.begin(), rows.end());
      return rows;
    }


    template <int dim, typename Number>
    void
    VelocityLevelOperator<dim, Number>::vmult_add(VectorType       &dst,
                                                  const VectorType &src) const
    {
      VectorType tmp;
      tmp.reinit(dst, true);
      vmult(tmp, src);
      dst += tmp;
    }


    template <int dim, typename Number>
    types::global_dof_index
    VelocityLevelOperator<dim, Number>::m() const
    {
      return matrix_free->get_dof_handler(dof_index).n_dofs();
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::reinit(
      std::shared_ptr<const MatrixFree<dim, Number>>           data,
      std::shared_ptr<const VelocityCoefficients<dim, Number>> coeff,
      const AffineConstraints<Number>                         &constraints_in,
      const unsigned int                                       dof,
      const unsigned int                                       quad)
    {
      this->matrix_free = data;
      this->dof_index   = dof;
      coefficients      = coeff;
      has_advection     = coeff->advection.size(0) > 0;
      has_newton        = coeff->advection_gradient.size(0) > 0;
      constraints       = &constraints_in;
      quad_index        = quad;
      constrained_local_dofs =
        constrained_local_rows(*data->get_vector_partitioner(dof),
                               constraints_in);
      system_matrix.clear();
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::do_quadrature(Evaluation &phi) const
    {
      const unsigned int cell = phi.get_current_cell_index();
      Tensor<1, dim, VectorizedArray<Number>> force;
      Tensor<2, dim, VectorizedArray<Number>> flux;
      for (const unsigned int q : phi.quadrature_point_indices())
        {
          quadrature_terms(
            cell, q, phi.get_value(q), phi.get_gradient(q), force, flux);
          phi.submit_value(force, q);
          phi.submit_gradient(flux, q);
        }
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::local_apply(
      const MatrixFree<dim, Number>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      Evaluation phi(data, range, this->dof_index, quad_index);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          phi.reinit(cell);
          phi.gather_evaluate(src,
                              EvaluationFlags::values |
                                EvaluationFlags::gradients);
          do_quadrature(phi);
          phi.integrate_scatter(EvaluationFlags::values |
                                  EvaluationFlags::gradients,
                                dst);
        }
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::vmult(VectorType       &dst,
                                                 const VectorType &src) const
    {
      this->matrix_free->cell_loop(
        &VelocityOperator::local_apply, this, dst, src, true);
      for (const unsigned int i : constrained_local_dofs)
        dst.local_element(i) = src.local_element(i);
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::initialize_dof_vector(
      VectorType &vector) const
    {
      this->matrix_free->initialize_dof_vector(vector, this->dof_index);
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::local_compute(Evaluation &phi) const
    {
      phi.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
      do_quadrature(phi);
      phi.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
    }


    template <int dim, int degree, typename Number>
    void
    VelocityOperator<dim, degree, Number>::compute_inverse_diagonal(
      VectorType &inverse_diagonal) const
    {
      this->matrix_free->initialize_dof_vector(inverse_diagonal,
                                               this->dof_index);
      MatrixFreeTools::compute_diagonal(*this->matrix_free,
                                        inverse_diagonal,
                                        &VelocityOperator::local_compute,
                                        this,
                                        this->dof_index,
                                        quad_index);
      for (const unsigned int i : constrained_local_dofs)
        inverse_diagonal.local_element(i) = 1.;
      for (auto &d : inverse_diagonal)
        d = (std::abs(d) > 0) ? 1. / d : 1.;
    }


    template <int dim, int degree, typename Number>
    const TrilinosWrappers::SparseMatrix &
    VelocityOperator<dim, degree, Number>::get_system_matrix() const
    {
      if (system_matrix.m() == 0)
        {
          const auto &dof_handler =
            this->matrix_free->get_dof_handler(this->dof_index);
          TrilinosWrappers::SparsityPattern dsp(
            dof_handler.locally_owned_dofs(),
            dof_handler.get_triangulation().get_communicator());
          // Without the Newton term the components do not couple: a third
          // of the entries (coarse level of the velocity multigrid). Rows
          // and columns of constrained DoFs (the grains' rigid nodes) keep
          // only their diagonal.
          const unsigned int           n_components = dof_handler.get_fe().n_components();
          Table<2, DoFTools::Coupling> coupling(n_components, n_components);
          for (unsigned int c = 0; c < n_components; ++c)
            for (unsigned int d = 0; d < n_components; ++d)
              coupling[c][d] = (c == d || has_newton) ? DoFTools::always :
                                                        DoFTools::none;
          DoFTools::make_sparsity_pattern(dof_handler,
                                          coupling,
                                          dsp,
                                          *constraints,
                                          false);
          dsp.compress();
          system_matrix.reinit(dsp);
          MatrixFreeTools::compute_matrix(*this->matrix_free,
                                          *constraints,
                                          system_matrix,
                                          &VelocityOperator::local_compute,
                                          this,
                                          this->dof_index,
                                          quad_index);
        }
      return system_matrix;
    }


    template <int dim>
    void
    StokesOperator<dim>::reinit(
      std::shared_ptr<const MatrixFree<dim, double>>          data,
      std::shared_ptr<const VelocityOperator<dim, 2, double>> velocity_block,
      const AffineConstraints<double> &velocity_constraints,
      const AffineConstraints<double> &pressure_constraints,
      const TrilinosWrappers::SparseMatrix *pressure_block)
    {
      matrix_free          = data;
      this->pressure_block = pressure_block;
      velocity    = velocity_block;
      constrained_velocity =
        constrained_local_rows(*data->get_vector_partitioner(0),
                               velocity_constraints);
      constrained_pressure =
        constrained_local_rows(*data->get_vector_partitioner(1),
                               pressure_constraints);
      velocity_extra = nullptr;
      skip_cell      = nullptr;
      step_velocity.clear();
      step_pressure.clear();
    }


    template <int dim>
    void
    StokesOperator<dim>::set_step_data(
      const std::vector<unsigned char>     *skip,
      const std::vector<unsigned int>      &velocity_rows,
      const std::vector<unsigned int>      &pressure_rows,
      const TrilinosWrappers::SparseMatrix *extra)
    {
      skip_cell      = skip;
      step_velocity  = velocity_rows;
      step_pressure  = pressure_rows;
      velocity_extra = extra;
    }


    template <int dim>
    void
    StokesOperator<dim>::zero_constrained_velocity_rows(VectorType &v) const
    {
      for (const unsigned int i : constrained_velocity)
        v.local_element(i) = 0;
      for (const unsigned int i : step_velocity)
        v.local_element(i) = 0;
    }


    template <int dim>
    void
    StokesOperator<dim>::copy_constrained_pressure_rows(
      VectorType       &dst,
      const VectorType &src) const
    {
      for (const unsigned int i : constrained_pressure)
        dst.local_element(i) = src.local_element(i);
      for (const unsigned int i : step_pressure)
        dst.local_element(i) = src.local_element(i);
    }


    template <int dim>
    void
    StokesOperator<dim>::zero_constrained_rows(BlockVectorType &v) const
    {
      zero_constrained_velocity_rows(v.block(0));
      for (const unsigned int i : constrained_pressure)
        v.block(1).local_element(i) = 0;
      for (const unsigned int i : step_pressure)
        v.block(1).local_element(i) = 0;
    }


    template <int dim>
    void
    StokesOperator<dim>::local_velocity(
      const MatrixFree<dim, double>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      typename VelocityOperator<dim, 2, double>::Evaluation u(data,
                                                              range,
                                                              0,
                                                              0);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          if (skip_cell != nullptr && (*skip_cell)[cell])
            continue;
          u.reinit(cell);
          u.gather_evaluate(src,
                            EvaluationFlags::values |
                              EvaluationFlags::gradients);
          velocity->do_quadrature(u);
          u.integrate_scatter(EvaluationFlags::values |
                                EvaluationFlags::gradients,
                              dst);
        }
    }


    template <int dim>
    void
    StokesOperator<dim>::vmult_velocity(VectorType       &dst,
                                        const VectorType &src) const
    {
      matrix_free->cell_loop(
        &StokesOperator::local_velocity, this, dst, src, true);
      if (velocity_extra != nullptr)
        {
          velocity_tmp.reinit(dst, true);
          velocity_extra->vmult(velocity_tmp, src);
          dst += velocity_tmp;
        }
      for (const unsigned int i : constrained_velocity)
        dst.local_element(i) = src.local_element(i);
      for (const unsigned int i : step_velocity)
        dst.local_element(i) = src.local_element(i);
    }


    template <int dim>
    template <bool plain>
    void
    StokesOperator<dim>::local_apply(
      const MatrixFree<dim, double>               &data,
      BlockVectorType                             &dst,
      const BlockVectorType                       &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      typename VelocityOperator<dim, 2, double>::Evaluation u(data,
                                                              range,
                                                              0,
                                                              0);
      FEEvaluation<dim, 1, 3, 1, double> p(data, range, 1, 0);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          if (!plain && skip_cell != nullptr && (*skip_cell)[cell])
            continue;
          u.reinit(cell);
          p.reinit(cell);
          if (plain)
            {
              u.read_dof_values_plain(src.block(0));
              p.read_dof_values_plain(src.block(1));
            }
          else
            {
              u.read_dof_values(src.block(0));
              p.read_dof_values(src.block(1));
            }
          u.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
          p.evaluate(EvaluationFlags::values);
          Tensor<1, dim, VectorizedArray<double>> force;
          Tensor<2, dim, VectorizedArray<double>> flux;
          for (const unsigned int q : u.quadrature_point_indices())
            {
              const auto grad = u.get_gradient(q);
              velocity->quadrature_terms(
                cell, q, u.get_value(q), grad, force, flux);
              // -(p, div v) joins the viscous flux on its diagonal.
              const auto pressure = p.get_value(q);
              for (unsigned int d = 0; d < dim; ++d)
                flux[d][d] -= pressure;
              u.submit_value(force, q);
              u.submit_gradient(flux, q);
              p.submit_value(-trace(grad), q);
            }
          u.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
          p.integrate(EvaluationFlags::values);
          if (plain)
            {
              // dst -= K src.
              for (unsigned int i = 0; i < u.dofs_per_cell; ++i)
                u.begin_dof_values()[i] *= -1.;
              for (unsigned int i = 0; i < p.dofs_per_cell; ++i)
                p.begin_dof_values()[i] *= -1.;
            }
          u.distribute_local_to_global(dst.block(0));
          p.distribute_local_to_global(dst.block(1));
        }
    }


    template <int dim>
    void
    StokesOperator<dim>::vmult(BlockVectorType       &dst,
                               const BlockVectorType &src) const
    {
      matrix_free->cell_loop(
        &StokesOperator::local_apply<false>, this, dst, src, true);
      if (pressure_block != nullptr)
        {
          // Constrained columns are not in the assembled block.
          pressure_tmp.reinit(dst.block(1), true);
          pressure_block->vmult(pressure_tmp, src.block(1));
          dst.block(1) += pressure_tmp;
        }
      if (velocity_extra != nullptr)
        {
          velocity_tmp.reinit(dst.block(0), true);
          velocity_extra->vmult(velocity_tmp, src.block(0));
          dst.block(0) += velocity_tmp;
        }
      for (const unsigned int i : constrained_velocity)
        dst.block(0).local_element(i) = src.block(0).local_element(i);
      for (const unsigned int i : constrained_pressure)
        dst.block(1).local_element(i) = src.block(1).local_element(i);
      for (const unsigned int i : step_velocity)
        dst.block(0).local_element(i) = src.block(0).local_element(i);
      for (const unsigned int i : step_pressure)
        dst.block(1).local_element(i) = src.block(1).local_element(i);
    }


    template <int dim>
    void
    StokesOperator<dim>::subtract_plain(BlockVectorType       &dst,
                                        const BlockVectorType &src) const
    {
      matrix_free->cell_loop(
        &StokesOperator::local_apply<true>, this, dst, src, false);
    }


    template <int dim>
    void
    StokesOperator<dim>::local_gradient(
      const MatrixFree<dim, double>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      typename VelocityOperator<dim, 2, double>::Evaluation u(data,
                                                              range,
                                                              0,
                                                              0);
      FEEvaluation<dim, 1, 3, 1, double> p(data, range, 1, 0);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          // All velocity nodes imposed: nothing reaches a free row.
          if (skip_cell != nullptr && (*skip_cell)[cell])
            continue;
          u.reinit(cell);
          p.reinit(cell);
          p.gather_evaluate(src, EvaluationFlags::values);
          for (const unsigned int q : u.quadrature_point_indices())
            u.submit_divergence(-p.get_value(q), q);
          u.integrate_scatter(EvaluationFlags::gradients, dst);
        }
    }


    template <int dim>
    void
    StokesOperator<dim>::apply_gradient(VectorType       &dst,
                                        const VectorType &pressure) const
    {
      matrix_free->cell_loop(
        &StokesOperator::local_gradient, this, dst, pressure, true);
    }


    template <int dim>
    void
    StokesOperator<dim>::local_divergence(
      const MatrixFree<dim, double>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      typename VelocityOperator<dim, 2, double>::Evaluation u(data,
                                                              range,
                                                              0,
                                                              0);
      FEEvaluation<dim, 1, 3, 1, double> p(data, range, 1, 0);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          // All velocity nodes imposed: nothing reaches a free row.
          if (skip_cell != nullptr && (*skip_cell)[cell])
            continue;
          u.reinit(cell);
          p.reinit(cell);
          u.gather_evaluate(src, EvaluationFlags::gradients);
          for (const unsigned int q : p.quadrature_point_indices())
            p.submit_value(-u.get_divergence(q), q);
          p.integrate_scatter(EvaluationFlags::values, dst);
        }
    }


    template <int dim>
    void
    StokesOperator<dim>::apply_divergence(VectorType       &dst,
                                          const VectorType &velocity) const
    {
      matrix_free->cell_loop(
        &StokesOperator::local_divergence, this, dst, velocity, true);
    }


    template <int dim>
    void
    StokesOperator<dim>::initialize_dof_vector(BlockVectorType &vector) const
    {
      vector.reinit(2);
      matrix_free->initialize_dof_vector(vector.block(0), 0);
      matrix_free->initialize_dof_vector(vector.block(1), 1);
      vector.collect_sizes();
    }


    template std::vector<unsigned int>
    constrained_local_rows(const Utilities::MPI::Partitioner &,
                           const AffineConstraints<double> &);
    template class VelocityLevelOperator<2, double>;
    template class VelocityLevelOperator<3, double>;
    template class VelocityOperator<2, 1, double>;
    template class VelocityOperator<2, 2, double>;
    template class VelocityOperator<3, 1, double>;
    template class VelocityOperator<3, 2, double>;
    template class StokesOperator<2>;
    template class StokesOperator<3>;
  } // namespace fluid
} // namespace softsand
