// The transient matrix-free step's reactions: the fluid force on each
// rigid node (and on the walls) from the residual F - K u of its rows,
// cell by cell with the step's own kernels (no second assembly), summed
// per row and then into one record per grain and owned node.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_tools.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/matrix_free/fe_evaluation.h>

#include <softsand/fluid/node_reactions.h>
#include <softsand/fluid/transient_matrix_free.h>

#include <algorithm>
#include <array>
#include <utility>

namespace softsand
{
  namespace fluid
  {
    using namespace internal;

    template <int dim>
    void
    PenalizedNavierStokes<dim>::compute_matrix_free_reactions(
      const unsigned int order)
    {
      using VectorType = LinearAlgebra::distributed::Vector<double>;
      using Evaluation = typename VelocityOperator<dim, 2, double>::Evaluation;
      TransientMatrixFree           &data        = *transient_matrix_free;
      const MatrixFree<dim, double> &matrix_free = *data.matrix_free;
      const auto &partitioner_u = *matrix_free.get_vector_partitioner(0);
      const unsigned int n_batches = matrix_free.n_cell_batches();
      const bool penalized = solid_field != nullptr && !constrains_solids();
      constexpr unsigned int n_q = Utilities::pow(3, dim);
      const auto &right_hand_side = data.right_hand_side;
      // Reactions: F - K u of the rigid nodes' rows (and of the hanging
      // nodes of rigid parents, split by their weights) and the residual
      // summed over the rows of velocity-constrained boundary faces, from
      // each cell's own terms as compute_reactions() (no second assembly).
      TimerOutput::Scope t(timer, "fluid: reactions");
      rigid_reactions.clear();
      // Each reaction row's residual, summed over its cells (rows of ghost
      // nodes go to their owners), then each owned node once: a hash
      // lookup per cell and node cost more than the cells' kernels.
      VectorType row_residual;
      matrix_free.initialize_dof_vector(row_residual, 0);
      struct ReactionNode
      {
        std::array<unsigned int, dim> local;
        Point<dim>                    position;
      };
      std::vector<ReactionNode> reaction_nodes;
      std::vector<bool>         listed(partitioner_u.locally_owned_size());
      VectorType u_full, p_full;
      data.copy_to_kernel_layout(solution, 0, u_full);
      data.copy_to_kernel_layout(solution, 1, p_full);
      u_full.update_ghost_values();
      p_full.update_ghost_values();
      VectorType traction_force;
      if (data.has_traction)
        {
          matrix_free.initialize_dof_vector(traction_force, 0);
          data.traction.vmult(traction_force, u_full);
          traction_force.update_ghost_values();
        }

      const std::vector<unsigned int> h2l =
        FETools::hierarchic_to_lexicographic_numbering<dim>(2);
      const unsigned int n_scalar = h2l.size();
      Evaluation         u(matrix_free, 0, 0), u_old(matrix_free, 0, 0),
        u_older(matrix_free, 0, 0);
      FEEvaluation<dim, 1, 3, 1, double> p(matrix_free, 1, 0);
      const Quadrature<dim> nodes(fe_velocity.get_unit_support_points());
      FEValues<dim>         node_values(data.mapping,
                                fe_velocity,
                                nodes,
                                update_quadrature_points);
      std::vector<types::global_dof_index> u_dofs(
        fe_velocity.n_dofs_per_cell());
      std::vector<bool> on_face(fe_velocity.n_dofs_per_cell());
      std::vector<Point<dim>>     points(n_q);
      std::vector<double>         void_fraction(n_q, 1.);
      std::vector<Tensor<1, dim>> solid_velocity(n_q);
      std::vector<int>            solid_index(n_q, -1);
      Tensor<1, dim>              boundary_force;
      const bool hanging_rigid = !hanging_rigid_parents.empty();
      const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
      FEFaceValues<dim>                face_values(data.mapping,
                                    fe_velocity,
                                    face_quadrature,
                                    update_values | update_normal_vectors |
                                      update_JxW_values);
      Vector<double> face_term(fe_velocity.n_dofs_per_cell());
      for (unsigned int batch = 0; batch < n_batches; ++batch)
        for (unsigned int lane = 0;
             lane < matrix_free.n_active_entries_per_cell_batch(batch);
             ++lane)
          {
            const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
            cell->get_dof_indices(u_dofs);
            // Rigid nodes and hanging nodes on rigid parents (flags 2, 4).
            bool has_rigid = false;
            for (const auto i : u_dofs)
              if (data.velocity_flags[partitioner_u.global_to_local(i)] & 6)
                {
                  has_rigid = true;
                  break;
                }
            std::fill(on_face.begin(), on_face.end(), false);
            bool on_wall = false;
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  boundary_conditions.imposes_velocity(
                    cell->face(f)->boundary_id()))
                {
                  on_wall = true;
                  for (unsigned int k = 0;
                       k < fe_velocity.n_dofs_per_face();
                       ++k)
                    on_face[fe_velocity.face_to_cell_index(k, f)] = true;
                }
            if (!has_rigid && !on_wall)
              continue;

            // The cell's K u - F, lexicographic per component.
            u.reinit(batch);
            p.reinit(batch);
            u.read_dof_values_plain(u_full);
            p.read_dof_values_plain(p_full);
            u.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
            p.evaluate(EvaluationFlags::values);
            const bool reservoir = data.reservoir[batch];
            if (!reservoir)
              {
                u_old.reinit(batch);
                u_old.read_dof_values_plain(data.old_velocity);
                u_old.evaluate(EvaluationFlags::values);
                if (order == 2)
                  {
                    u_older.reinit(batch);
                    u_older.read_dof_values_plain(data.older_velocity);
                    u_older.evaluate(EvaluationFlags::values);
                  }
                for (unsigned int q = 0; q < n_q; ++q)
                  for (unsigned int d = 0; d < dim; ++d)
                    points[q][d] = u.quadrature_point(q)[d][lane];
                if (penalized)
                  evaluate_solids(*cell,
                                  points,
                                  void_fraction,
                                  solid_velocity,
                                  solid_index);
              }
            const PorousCell<dim> porous =
              reservoir ? PorousCell<dim>() : porous_cell(*cell);
            const Tensor<1, dim> grain_flux = porous.grain_flux();
            Tensor<1, dim, VectorizedArray<double>> force;
            Tensor<2, dim, VectorizedArray<double>> flux;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const auto grad = u.get_gradient(q);
                data.velocity_operator->quadrature_terms(
                  batch, q, u.get_value(q), grad, force, flux);
                const auto pressure = p.get_value(q);
                for (unsigned int d = 0; d < dim; ++d)
                  flux[d][d] -= pressure;
                if (!reservoir)
                  {
                    // Minus the right-hand side of assemble().
                    Tensor<1, dim> u_o, u_oo;
                    const auto     v1 = u_old.get_value(q);
                    for (unsigned int d = 0; d < dim; ++d)
                      u_o[d] = v1[d][lane];
                    if (order == 2)
                      {
                        const auto v2 = u_older.get_value(q);
                        for (unsigned int d = 0; d < dim; ++d)
                          u_oo[d] = v2[d][lane];
                      }
                    // Porous cells: the history by alpha / phi, as in
                    // the step's assembly.
                    Tensor<1, dim> right = right_hand_side(
                      points[q], porous.inertia_scale * u_o,
                      porous.inertia_scale * u_oo, void_fraction[q],
                      solid_velocity[q]);
                    // The porous drag's share, as in the step's assembly.
                    if (porous.porous)
                      right += porous.drag(fluid_parameters.viscosity,
                                           right_hand_side.rho,
                                           right_hand_side.bdf.e1 * u_o +
                                             right_hand_side.bdf.e2 * u_oo -
                                             grain_flux) *
                               grain_flux;
                    for (unsigned int d = 0; d < dim; ++d)
                      force[d][lane] -= right[d];
                  }
                u.submit_value(force, q);
                u.submit_gradient(flux, q);
              }
            u.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
            const auto residual = [&](const unsigned int i) {
              const auto [c, b] = fe_velocity.system_to_component_index(i);
              return -u.begin_dof_values()[c * n_scalar + h2l[b]][lane];
            };

            if (has_rigid)
              {
                bool positioned = false;
                for (unsigned int i = 0; i < u_dofs.size(); ++i)
                  {
                    const unsigned int local =
                      partitioner_u.global_to_local(u_dofs[i]);
                    if (!(data.velocity_flags[local] & 6))
                      continue;
                    row_residual.local_element(local) += residual(i);
                    // The node by its first component's DoF, listed by
                    // the first owned cell that reaches it.
                    const unsigned int base =
                      fe_velocity.system_to_component_index(i).second;
                    const unsigned int first =
                      fe_velocity.component_to_system_index(0, base);
                    const unsigned int first_local =
                      partitioner_u.global_to_local(u_dofs[first]);
                    if (first_local >= listed.size() || listed[first_local])
                      continue;
                    listed[first_local] = true;
                    if (!positioned)
                      {
                        node_values.reinit(cell);
                        positioned = true;
                      }
                    ReactionNode node;
                    for (unsigned int c = 0; c < dim; ++c)
                      node.local[c] = partitioner_u.global_to_local(
                        u_dofs[fe_velocity.component_to_system_index(c,
                                                                     base)]);
                    node.position = node_values.quadrature_point(first);
                    reaction_nodes.push_back(node);
                  }
              }
            if (on_wall)
              {
                for (unsigned int i = 0; i < u_dofs.size(); ++i)
                  if (on_face[i])
                    boundary_force[fe_velocity.system_to_component_index(i)
                                     .first] += residual(i);
                // The pressure faces' -p_b (v . n) in those rows' F.
                for (const auto f : cell->face_indices())
                  if (cell->face(f)->at_boundary() &&
                      boundary_conditions.face(cell->face(f)->boundary_id())
                          .type == BoundaryConditions<dim>::Type::pressure)
                    {
                      const double p_b =
                        boundary_conditions
                          .face(cell->face(f)->boundary_id())
                          .pressure;
                      face_values.reinit(cell, f);
                      face_term = 0;
                      add_pressure_face_term(face_values, p_b, face_term);
                      for (unsigned int i = 0; i < u_dofs.size(); ++i)
                        if (on_face[i])
                          boundary_force
                            [fe_velocity.system_to_component_index(i)
                               .first] += face_term(i);
                    }
              }
          }
      row_residual.compress(VectorOperation::add);
      // Each node's reaction, split among the grains of its target (rigid
      // node) or of its parents (hanging node); a rigid node's row also
      // takes the traction faces' term, which acts on rows, not cells.
      std::vector<std::pair<int, Tensor<1, dim>>> grain_sums;
      for (const auto &node : reaction_nodes)
        {
          grain_sums.clear();
          for (unsigned int c = 0; c < dim; ++c)
            {
              const unsigned int local = node.local[c];
              if (!(data.velocity_flags[local] & 6))
                continue;
              const types::global_dof_index i =
                partitioner_u.local_to_global(local);
              const auto add = [&](const int grain, const double value) {
                auto sum = std::find_if(grain_sums.begin(),
                                        grain_sums.end(),
                                        [grain](const auto &g) {
                                          return g.first == grain;
                                        });
                if (sum == grain_sums.end())
                  sum = grain_sums.emplace(grain_sums.end(),
                                           grain,
                                           Tensor<1, dim>());
                sum->second[c] += value;
              };
              const double r = row_residual.local_element(local);
              if (rigid_dof_grain.count(i))
                {
                  const double traction =
                    data.has_traction ? traction_force.local_element(local) :
                                        0.;
                  for_each_grain_share(
                    rigid_dof_grain, rigid_dof_shares, i, r - traction, add);
                }
              if (hanging_rigid)
                {
                  const auto hanging = hanging_rigid_parents.find(i);
                  if (hanging != hanging_rigid_parents.end())
                    for (const auto &[parent, weight] : hanging->second)
                      for_each_grain_share(rigid_dof_grain,
                                           rigid_dof_shares,
                                           parent,
                                           weight * r,
                                           add);
                }
            }
          for (const auto &[grain, force] : grain_sums)
            rigid_reactions.emplace_back(grain, node.position, force);
        }
      boundary_force += pressure_face_force();
      last_boundary_force =
        Utilities::MPI::sum(boundary_force, mpi_communicator);
    }


    template void
    PenalizedNavierStokes<2>::compute_matrix_free_reactions(const unsigned int);
    template void
    PenalizedNavierStokes<3>::compute_matrix_free_reactions(const unsigned int);
  } // namespace fluid
} // namespace softsand
