// The transient matrix-free step of PenalizedNavierStokes (fluid solver/
// transient solver = matrix free): the BDF step of the penalized
// Navier-Stokes equations (the Oseen system of assemble(), Assembly::
// transient) solved without assembling the Q2-Q1 matrix. Its phases:
//  - assemble (this file): the grains' rigid nodes (and pinned pressures)
//    become identity rows of the operator, their values a lifting; cells
//    whose velocity nodes are all imposed are skipped; the coefficients at
//    the quadrature points (BDF mass, Temam term, advecting velocity) and
//    the right-hand side from the history; the traction faces' convective
//    term rho/2 |(w . n)_-| (u, v) and the rigid-node pressure smoothing
//    -C, assembled (faces and cut cells only);
//  - the preconditioner and the solve (transient_matrix_free_solve.cc);
//  - the fluid force on each rigid node and the walls from the residual of
//    their rows (transient_matrix_free_reactions.cc).
// What is kept while the mesh is: transient_matrix_free_setup.cc.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/matrix_free/fe_evaluation.h>

#include <softsand/base/warnings.h>
#include <softsand/fluid/box_cell_tensors.h>
#include <softsand/fluid/transient_matrix_free.h>

namespace softsand
{
  namespace fluid
  {
    using namespace internal;

    template <int dim>
    unsigned int
    PenalizedNavierStokes<dim>::advance_matrix_free(const double       dt,
                                                    const unsigned int order)
    {
      if (transient_matrix_free == nullptr)
        setup_transient_matrix_free();
      assemble_matrix_free_step(dt, order);
      setup_matrix_free_preconditioner(dt, order);
      solve_matrix_free_step();
      compute_matrix_free_reactions(order);
      return statistics.linear_iterations;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::assemble_matrix_free_step(
      const double       dt,
      const unsigned int order)
    {
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;
      using Evaluation = typename VelocityOperator<dim, 2, double>::Evaluation;
      TransientMatrixFree           &data        = *transient_matrix_free;
      const MatrixFree<dim, double> &matrix_free = *data.matrix_free;
      const types::global_dof_index  n_u = dof_handler_velocity.n_dofs();
      const unsigned int             n_batches = matrix_free.n_cell_batches();
      const double rho = fluid_parameters.density;
      const BDFCoefficients bdf = bdf_coefficients(order, bdf_step_ratio);
      const bool            penalized = solid_field != nullptr && !constrains_solids();
      constexpr unsigned int n_p = LocalTensors<dim>::n_p;
      constexpr unsigned int n_q = Utilities::pow(3, dim);
      auto &right_hand_side          = data.right_hand_side;
      right_hand_side.rho            = rho;
      right_hand_side.theta          = fluid_parameters.theta;
      right_hand_side.dt             = dt;
      right_hand_side.bdf            = bdf;
      right_hand_side.body_force     =
        data.constant_body_force ? nullptr : body_force.get();
      right_hand_side.constant_force = data.body_force_value;
      const auto &partitioner_u = *matrix_free.get_vector_partitioner(0);
      const auto &partitioner_p = *matrix_free.get_vector_partitioner(1);
      const unsigned int owned_u = partitioner_u.locally_owned_size();
      const unsigned int owned_p = partitioner_p.locally_owned_size();

      BlockVectorType &rhs = data.rhs, &lifting = data.lifting;
      for (BlockVectorType *v : {&rhs, &lifting})
        {
          v->reinit(2);
          matrix_free.initialize_dof_vector(v->block(0), 0);
          matrix_free.initialize_dof_vector(v->block(1), 1);
          v->collect_sizes();
        }
      TimerOutput::Scope t(timer, "fluid: assemble");

      // This step's constraints: imposed and rigid velocity nodes, the
      // rows only this step constrains (grains), and the lifting that
      // carries every constrained value.
      data.velocity_flags.assign(owned_u + partitioner_u.n_ghost_indices(),
                                 0);
      data.step_velocity.clear();
      data.step_pressure.clear();
      for (const auto &line : constraints.get_lines())
        if (line.index < n_u)
          {
            if (!partitioner_u.in_local_range(line.index) &&
                !partitioner_u.is_ghost_entry(line.index))
              continue;
            const unsigned int i = partitioner_u.global_to_local(line.index);
            if (line.entries.empty())
              data.velocity_flags[i] |= 1;
            if (i < owned_u)
              {
                lifting.block(0).local_element(i) = line.inhomogeneity;
                if (!data.velocity_constraints.is_constrained(line.index))
                  data.step_velocity.push_back(i);
              }
          }
        else
          {
            const types::global_dof_index g = line.index - n_u;
            if (!partitioner_p.in_local_range(g))
              continue;
            const unsigned int i = partitioner_p.global_to_local(g);
            lifting.block(1).local_element(i) = line.inhomogeneity;
            if (!data.pressure_constraints.is_constrained(g))
              data.step_pressure.push_back(i);
          }
      for (const auto &[i, grain] : rigid_dof_grain)
        if (partitioner_u.in_local_range(i) || partitioner_u.is_ghost_entry(i))
          data.velocity_flags[partitioner_u.global_to_local(i)] |= 2;
      for (const auto &[i, parents] : hanging_rigid_parents)
        if (partitioner_u.in_local_range(i) || partitioner_u.is_ghost_entry(i))
          data.velocity_flags[partitioner_u.global_to_local(i)] |= 4;

      // The history on the kernels' layout.
      data.copy_to_kernel_layout(old_solution, 0, data.old_velocity);
      data.old_velocity.update_ghost_values();
      if (order == 2)
        {
          data.copy_to_kernel_layout(older_solution, 0, data.older_velocity);
          data.older_velocity.update_ghost_values();
        }
      else
        data.older_velocity.reinit(0);

      // Coefficients at the quadrature points and the right-hand side.
      auto &coefficients = *data.coefficients;
      coefficients.reaction.reinit(n_batches, n_q);
      coefficients.advection.reinit(n_batches, n_q);
      coefficients.viscosity_scale.resize(0);
      coefficients.viscosity_scale.resize(n_batches,
                                          VectorizedArray<double>(1.));
      data.skip.assign(n_batches, 0);
      Evaluation phi(matrix_free, 0, 0), phi_old(matrix_free, 0, 0),
        phi_older(matrix_free, 0, 0);
      std::vector<types::global_dof_index> u_dofs(
        fe_velocity.n_dofs_per_cell());
      std::vector<Point<dim>>     points(n_q);
      std::vector<double>         void_fraction(n_q, 1.);
      std::vector<Tensor<1, dim>> solid_velocity(n_q);
      std::vector<int>            solid_index(n_q, -1);
      Vector<double>              force_value(dim);
      AlignedVector<Tensor<1, dim, VectorizedArray<double>>> rhs_values(n_q);
      for (unsigned int batch = 0; batch < n_batches; ++batch)
        {
          // Skipped: every velocity node of every lane imposed.
          bool all_fixed = true;
          for (unsigned int lane = 0;
               lane < matrix_free.n_active_entries_per_cell_batch(batch) &&
               all_fixed;
               ++lane)
            {
              matrix_free.get_cell_iterator(batch, lane, 0)
                ->get_dof_indices(u_dofs);
              for (const auto i : u_dofs)
                if (!(data.velocity_flags[partitioner_u.global_to_local(i)] &
                      1))
                  {
                    all_fixed = false;
                    break;
                  }
            }
          data.skip[batch] = all_fixed;
          if (data.reservoir[batch])
            {
              // Only the pressure term -(p, div v) (PressureRegion).
              coefficients.viscosity_scale[batch] = 0.;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  coefficients.reaction(batch, q)  = 0.;
                  coefficients.advection(batch, q) =
                    Tensor<1, dim, VectorizedArray<double>>();
                }
              continue;
            }
          phi.reinit(batch);
          phi_old.reinit(batch);
          phi_old.read_dof_values_plain(data.old_velocity);
          phi_old.evaluate(EvaluationFlags::values |
                           EvaluationFlags::gradients);
          if (order == 2)
            {
              phi_older.reinit(batch);
              phi_older.read_dof_values_plain(data.older_velocity);
              phi_older.evaluate(EvaluationFlags::values |
                                 EvaluationFlags::gradients);
            }
          for (unsigned int lane = 0;
               lane < matrix_free.n_active_entries_per_cell_batch(batch);
               ++lane)
            {
              for (unsigned int q = 0; q < n_q; ++q)
                for (unsigned int d = 0; d < dim; ++d)
                  points[q][d] = phi.quadrature_point(q)[d][lane];
              if (penalized)
                evaluate_solids(*matrix_free.get_cell_iterator(batch, lane, 0),
                                points,
                                void_fraction,
                                solid_velocity,
                                solid_index);
              // The hybrid model's porous cells: a drag instead of grains.
              const PorousCell<dim> porous =
                porous_cell(*matrix_free.get_cell_iterator(batch, lane, 0));
              const Tensor<1, dim> grain_flux = porous.grain_flux();
              // The superficial velocity's momentum equation: the pore
              // fluid's inertia and viscosity, rho alpha / phi d u / dt and
              // mu / phi lap u (phi = 1 outside the porous zone). The
              // convection keeps rho: Temam's skew form is energy-neutral
              // only with one coefficient on both sides of a face (with
              // rho / phi^2 the resolved zone's edge blew up at 16 kPa).
              const double inverse_porosity = 1. / porous.porosity;
              coefficients.viscosity_scale[batch][lane] = inverse_porosity;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  Tensor<1, dim> u_old, u_older;
                  double         div_old = 0, div_older = 0;
                  const auto     value   = phi_old.get_value(q);
                  const auto     grad    = phi_old.get_gradient(q);
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      u_old[d] = value[d][lane];
                      div_old += grad[d][d][lane];
                    }
                  if (order == 2)
                    {
                      const auto v2 = phi_older.get_value(q);
                      const auto g2 = phi_older.get_gradient(q);
                      for (unsigned int d = 0; d < dim; ++d)
                        {
                          u_older[d] = v2[d][lane];
                          div_older += g2[d][d][lane];
                        }
                    }
                  const double vf    = void_fraction[q];
                  const double solid = 1. - vf;
                  const double rho_star =
                    rho * (1. + fluid_parameters.theta * solid);
                  const Tensor<1, dim> w =
                    bdf.e1 * u_old + bdf.e2 * u_older;
                  const double div_w = bdf.e1 * div_old + bdf.e2 * div_older;
                  const double drag =
                    porous.porous ?
                      porous.drag(fluid_parameters.viscosity, rho,
                                  w - grain_flux) :
                      0.;
                  const double p1 = porous.inertia_scale;
                  coefficients.reaction(batch, q)[lane] =
                    p1 * bdf.a0 * rho_star / dt + 0.5 * rho * div_w + drag;
                  for (unsigned int d = 0; d < dim; ++d)
                    coefficients.advection(batch, q)[d][lane] = rho * w[d];
                  const Tensor<1, dim> right =
                    right_hand_side(points[q],
                                    p1 * u_old,
                                    p1 * u_older,
                                    vf,
                                    solid_velocity[q]) +
                    drag * grain_flux;
                  for (unsigned int d = 0; d < dim; ++d)
                    rhs_values[q][d][lane] = right[d];
                }
            }
          for (unsigned int q = 0; q < n_q; ++q)
            phi.submit_value(rhs_values[q], q);
          phi.integrate_scatter(EvaluationFlags::values, rhs.block(0));
        }
      rhs.block(0).compress(VectorOperation::add);
      rhs.block(0) += data.face_rhs;
      data.velocity_operator->reinit(data.matrix_free,
                                     data.coefficients,
                                     data.velocity_constraints,
                                     0,
                                     0);

      // Traction faces: rho/2 |(w . n)_-| (u, v) with this step's w.
      if (data.has_traction)
        {
          data.traction = 0;
          const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
          FEFaceValues<dim>                face_values(data.mapping,
                                        fe_velocity,
                                        face_quadrature,
                                        update_values |
                                          update_normal_vectors |
                                          update_JxW_values);
          FESubfaceValues<dim>             subface_values(data.mapping,
                                              fe_velocity,
                                              face_quadrature,
                                              update_values |
                                                update_normal_vectors |
                                                update_JxW_values);
          const FEValuesExtractors::Vector velocities(0);
          FullMatrix<double> local(fe_velocity.n_dofs_per_cell(),
                                   fe_velocity.n_dofs_per_cell());
          std::vector<Tensor<1, dim>> w(face_quadrature.size()),
            w_older(face_quadrature.size());
          for (const auto &[batch, lane, f, sf] : data.traction_faces)
            {
              const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
              const FEFaceValuesBase<dim> &values =
                sf < 0 ? static_cast<const FEFaceValuesBase<dim> &>(
                           face_values) :
                         static_cast<const FEFaceValuesBase<dim> &>(
                           subface_values);
              if (sf < 0)
                face_values.reinit(cell, f);
              else
                subface_values.reinit(cell, f, sf);
              values[velocities].get_function_values(data.old_velocity, w);
              if (order == 2)
                {
                  values[velocities].get_function_values(
                    data.older_velocity, w_older);
                  for (unsigned int q = 0; q < w.size(); ++q)
                    w[q] = bdf.e1 * w[q] + bdf.e2 * w_older[q];
                }
              local = 0;
              for (unsigned int q = 0; q < w.size(); ++q)
                {
                  const double w_n = w[q] * values.normal_vector(q);
                  if (w_n >= 0)
                    continue;
                  const double weight = -0.5 * rho * w_n * values.JxW(q);
                  for (unsigned int i = 0; i < local.m(); ++i)
                    {
                      const double phi_i = values.shape_value(i, q);
                      if (phi_i == 0)
                        continue;
                      const unsigned int ci =
                        fe_velocity.system_to_component_index(i).first;
                      for (unsigned int j = 0; j < local.n(); ++j)
                        if (fe_velocity.system_to_component_index(j).first ==
                            ci)
                          local(i, j) +=
                            weight * phi_i * values.shape_value(j, q);
                    }
                }
              cell->get_dof_indices(u_dofs);
              data.velocity_constraints.distribute_local_to_global(
                local, u_dofs, data.traction);
            }
          data.traction.compress(VectorOperation::add);
        }

      // The rigid-node pressure smoothing -C in cut cells, lifted with
      // the regions' pressures.
      LocalTensors<dim>        local_tensors;
      LocalTensorComputer<dim> tensor_computer;
      std::vector<types::global_dof_index> p_dofs(n_p);
      if (data.has_smoothing)
        {
          data.smoothing = 0;
          // The penalization limit's squeeze relaxation, as assemble().
          const bool squeeze = relaxes_squeezes();
          std::unique_ptr<FEValues<dim>> squeeze_values;
          std::vector<unsigned int>      component(u_dofs.size());
          if (squeeze)
            {
              squeeze_values = std::make_unique<FEValues<dim>>(
                data.mapping,
                fe_velocity,
                QGauss<dim>(fe_velocity.degree + 1),
                update_gradients | update_JxW_values);
              for (unsigned int k = 0; k < component.size(); ++k)
                component[k] = fe_velocity.system_to_component_index(k).first;
            }
          FullMatrix<double> local(n_p, n_p);
          Vector<double>     local_rhs(n_p);
          for (unsigned int batch = 0; batch < n_batches; ++batch)
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
                cell->get_dof_indices(u_dofs);
                unsigned int n_rigid = 0, n_fixed = 0;
                for (const auto i : u_dofs)
                  {
                    const unsigned char flag =
                      data.velocity_flags[partitioner_u.global_to_local(i)];
                    n_rigid += (flag & 2) ? 1 : 0;
                    n_fixed += (flag & 1) ? 1 : 0;
                  }
                if (n_rigid == 0)
                  continue;
                const double h = cell->diameter() / std::sqrt(double(dim));
                double weight =
                  rigid_cell_weights(u_dofs.size(), n_rigid, n_fixed, h)
                    .second;
                if (weight == 0)
                  continue;
                if (squeeze)
                  {
                    squeeze_values->reinit(cell);
                    weight *=
                      squeeze_factor(*squeeze_values, u_dofs, component, h);
                  }
                tensor_computer.compute(cell, local_tensors);
                for (unsigned int a = 0; a < n_p; ++a)
                  for (unsigned int b = 0; b < n_p; ++b)
                    local(a, b) =
                      -weight * local_tensors.pressure_laplace(a, b);
                local_rhs = 0;
                matrix_free.get_cell_iterator(batch, lane, 1)
                  ->get_dof_indices(p_dofs);
                data.pressure_values.distribute_local_to_global(
                  local, local_rhs, p_dofs, data.smoothing, rhs.block(1));
              }
          data.smoothing.compress(VectorOperation::add);
          rhs.block(1).compress(VectorOperation::add);
        }
      data.stokes.reinit(data.matrix_free,
                         data.velocity_operator,
                         data.velocity_constraints,
                         data.pressure_constraints,
                         data.has_smoothing ? &data.smoothing : nullptr);
      data.stokes.set_step_data(&data.skip,
                                data.step_velocity,
                                data.step_pressure,
                                data.has_traction ? &data.traction : nullptr);

      // The lifting: rhs -= K g for the constrained values g (the cell
      // terms read plainly; the traction term through its matrix).
      lifting.update_ghost_values();
      data.stokes.subtract_plain(rhs, lifting);
      if (data.has_traction)
        {
          VectorType tmp;
          tmp.reinit(rhs.block(0), true);
          data.traction.vmult(tmp, lifting.block(0));
          rhs.block(0) -= tmp;
        }
      data.stokes.zero_constrained_rows(rhs);

      if (!boundary_conditions.has_pressure_face())
        {
          // As solve_linear(): project the continuity rows onto the range.
          std::vector<bool> constrained(owned_p, false);
          for (const auto &line : data.pressure_constraints.get_lines())
            if (partitioner_p.in_local_range(line.index))
              constrained[partitioner_p.global_to_local(line.index)] = true;
          for (const auto i : data.step_pressure)
            constrained[i] = true;
          double       sum   = 0;
          unsigned int count = 0;
          for (unsigned int i = 0; i < owned_p; ++i)
            if (!constrained[i])
              {
                sum += rhs.block(1).local_element(i);
                ++count;
              }
          sum   = Utilities::MPI::sum(sum, mpi_communicator);
          count = Utilities::MPI::sum(count, mpi_communicator);
          for (unsigned int i = 0; i < owned_p; ++i)
            if (!constrained[i])
              rhs.block(1).local_element(i) -= sum / count;
        }
    }


    template unsigned int
    PenalizedNavierStokes<2>::advance_matrix_free(const double, const unsigned int);
    template unsigned int
    PenalizedNavierStokes<3>::advance_matrix_free(const double, const unsigned int);
    template void
    PenalizedNavierStokes<2>::assemble_matrix_free_step(const double, const unsigned int);
    template void
    PenalizedNavierStokes<3>::assemble_matrix_free_step(const double, const unsigned int);
  } // namespace fluid
} // namespace softsand
