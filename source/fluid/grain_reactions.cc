// PenalizedNavierStokes: the fluid's force on the grains and walls, from
// the reactions of the rows they fix (and the paper's Eq. 7 diagnostic).

#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/node_reactions.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/base/parameter_tools.h>
#include <softsand/base/warnings.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>
#include <set>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    void
    PenalizedNavierStokes<dim>::compute_reactions(const Assembly     kind,
                                                  const double       dt,
                                                  const unsigned int bdf_order)
    {
      // One assembly pass over the cells that carry either reaction: the
      // rigid nodes' (F - A u of each constrained node's row: the force of
      // the fluid on that node) and the velocity-constrained boundary
      // faces' (the same residual summed over their rows).
      rigid_reactions.clear();
      // Every rank decides alike: assemble() below has collectives, and a
      // rank without rigid nodes (or without cells) must still reach them.
      const bool rigid = Utilities::MPI::max(rigid_dof_grain.empty() ? 0u : 1u,
                                             mpi_communicator) != 0;
      const Quadrature<dim> nodes(fe.get_unit_support_points());
      FEValues<dim>  fe_values(fe, nodes, update_quadrature_points);
      Vector<double> local_solution(fe.n_dofs_per_cell());
      Tensor<1, dim> force;
      NodeReactionSum<dim> node_reactions;
      node_reactions.reserve(rigid_dof_grain.size() / dim +
                             hanging_rigid_parents.size());

      const auto add_rigid_reactions =
        [&](const typename DoFHandler<dim>::active_cell_iterator &cell,
            const FullMatrix<double>                             &matrix,
            const Vector<double>                                 &rhs,
            const std::vector<types::global_dof_index>           &dofs) {
          fe_values.reinit(cell);
          const auto add = [&](const unsigned int k, const int grain,
                               const double weight) {
            // Force of the fluid on the node: F_k - (A u)_k.
            double r = rhs(k);
            for (unsigned int j = 0; j < dofs.size(); ++j)
              r -= matrix(k, j) * local_solution(j);
            // The node by its first component's DoF.
            const auto [c, base] = fe.system_to_component_index(k);
            node_reactions.add(grain,
                               dofs[fe.component_to_system_index(0, base)],
                               fe_values.quadrature_point(k),
                               c,
                               weight * r);
          };
          // A node whose target blends grains (penalization limit) hands
          // each its share of the reaction.
          const auto add_node = [&](const unsigned int            k,
                                    const types::global_dof_index i,
                                    const double                  weight) {
            for_each_grain_share(rigid_dof_grain,
                                 rigid_dof_shares,
                                 i,
                                 weight,
                                 [&](const int grain, const double w) {
                                   add(k, grain, w);
                                 });
          };
          for (unsigned int k = 0; k < dofs.size(); ++k)
            {
              if (rigid_dof_grain.count(dofs[k]))
                add_node(k, dofs[k], 1.);
              const auto hanging = hanging_rigid_parents.find(dofs[k]);
              if (hanging != hanging_rigid_parents.end())
                for (const auto &[parent, weight] : hanging->second)
                  add_node(k, parent, weight);
            }
        };
      // assemble() asks the filter about a cell right before it hands that
      // cell to the callback: its answers (cell_has_rigid_nodes,
      // cell_on_wall, on_face) are kept for it. Only the rows the callback
      // reads are computed: rigid nodes and hanging nodes of rigid parents
      // (where reactions live), velocity nodes on constrained faces.
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<bool> on_face(fe.n_dofs_per_cell());
      bool cell_has_rigid_nodes = false, cell_on_wall = false;
      const CellFilter either = [&](const auto &cell, std::vector<bool> &rows) {
        std::fill(rows.begin(), rows.end(), false);
        cell_has_rigid_nodes = false;
        if (rigid)
          {
            cell->get_dof_indices(cell_dofs);
            for (unsigned int k = 0; k < rows.size(); ++k)
              if (rigid_dof_grain.count(cell_dofs[k]) ||
                  hanging_rigid_parents.count(cell_dofs[k]))
                rows[k] = cell_has_rigid_nodes = true;
          }
        std::fill(on_face.begin(), on_face.end(), false);
        cell_on_wall = false;
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              boundary_conditions.imposes_velocity(cell->face(f)->boundary_id()))
            {
              cell_on_wall = true;
              for (unsigned int k = 0; k < fe.n_dofs_per_face(); ++k)
                {
                  const unsigned int i = fe.face_to_cell_index(k, f);
                  if (fe.system_to_component_index(i).first < dim)
                    on_face[i] = rows[i] = true;
                }
            }
        return cell_has_rigid_nodes || cell_on_wall;
      };
      // The residual summed over the velocity rows on constrained faces.
      const auto add_boundary_reaction =
        [&](const FullMatrix<double> &matrix, const Vector<double> &rhs) {
          for (unsigned int k = 0; k < on_face.size(); ++k)
            if (on_face[k])
              {
                double r = rhs(k);
                for (unsigned int j = 0; j < on_face.size(); ++j)
                  r -= matrix(k, j) * local_solution(j);
                force[fe.system_to_component_index(k).first] += r;
              }
        };
      const CellCallback both =
        [&](const typename DoFHandler<dim>::active_cell_iterator &cell,
            const FullMatrix<double>                             &matrix,
            const Vector<double>                                 &rhs,
            const std::vector<types::global_dof_index>           &dofs) {
          cell->get_dof_values(solution, local_solution);
          if (cell_has_rigid_nodes)
            add_rigid_reactions(cell, matrix, rhs, dofs);
          if (cell_on_wall)
            add_boundary_reaction(matrix, rhs);
        };
      assemble(kind, dt, bdf_order, &both, &either);
      node_reactions.move_to(rigid_reactions);

      force += pressure_face_force();
      last_boundary_force = Utilities::MPI::sum(force, mpi_communicator);
    }


    template <int dim>
    Tensor<1, dim>
    PenalizedNavierStokes<dim>::pressure_face_force() const
    {
      // Pressure faces: the fluid pushes with p_b on the outward normal,
      // integrated over the mesh's faces (a cylinder's end is a 32-gon, a
      // mesh file's faces need not be planes of the box), so that a uniform
      // pressure exerts no net force.
      Tensor<1, dim>    force;
      FEFaceValues<dim> face_values(fe,
                                    QGauss<dim - 1>(2),
                                    update_normal_vectors | update_JxW_values);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                !boundary_conditions.imposes_velocity(
                  cell->face(f)->boundary_id()))
              {
                face_values.reinit(cell, f);
                const double p_b =
                  boundary_conditions.face(cell->face(f)->boundary_id())
                    .pressure;
                for (unsigned int q = 0; q < face_values.n_quadrature_points;
                     ++q)
                  force += p_b * face_values.normal_vector(q) *
                           face_values.JxW(q);
              }
      return force;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::for_each_solid_reaction(
      const std::function<void(const int,
                               const Point<dim> &,
                               const Tensor<1, dim> &)> &f) const
    {
      if (solid_field == nullptr)
        return;
      // Constrained nodes: the discrete reaction of their rows; with
      // constrained interiors it adds to the penalty reaction below (which
      // vanishes inside, where u = u_s), and the two together are the force
      // of the fluid on the grain.
      for (const auto &[grain, point, force] : rigid_reactions)
        f(grain, point, force);
      if (constrains_solids())
        return;
      // The penalty force density g = rho* (1 - vf) E / dt on the fluid,
      // less the physical inertia of the fluid the grain displaces, with
      // E = u^{n+1} - u~ (BDF1; BDF2 alike) and u~ = vf u^n + (1 - vf) u_s.
      // E stays small when the grain accelerates (the covered fluid follows
      // it within the step), whereas rho* (1 - vf)(u^{n+1} - u_s) / dt
      // would charge the grain with the fictitious inertia rho Theta of the
      // covered fluid. Steady: the Brinkman term beta (u - u_s), the fixed
      // point of the transient scheme (the two agree to O(1/Theta)).
      const FEValuesExtractors::Vector velocities(0);
      std::vector<Tensor<1, dim>>      u, u_old, u_older;
      std::vector<Tensor<1, dim>>      g;
      const double                     rho = fluid_parameters.density;
      const double rho_theta = fluid_parameters.density * fluid_parameters.theta;
      const BDFCoefficients bdf =
        bdf_coefficients(last_bdf_order, bdf_step_ratio);
      const auto penalty_density = [&](const FEValues<dim>               &fe_values,
                                       const std::vector<double>         &vf,
                                       const std::vector<Tensor<1, dim>> &u_s,
                                       const std::vector<int>            &index) {
        const unsigned int n_q = vf.size();
        u.resize(n_q);
        g.assign(n_q, Tensor<1, dim>());
        fe_values[velocities].get_function_values(solution, u);
        if (!last_was_steady)
          {
            u_old.resize(n_q);
            u_older.resize(n_q);
            fe_values[velocities].get_function_values(old_solution, u_old);
            fe_values[velocities].get_function_values(older_solution, u_older);
          }
        for (unsigned int q = 0; q < n_q; ++q)
          if (index[q] >= 0 && vf[q] < 1)
            {
              const double   solid = 1. - vf[q];
              Tensor<1, dim> E;
              if (last_was_steady)
                E = u[q] - u_s[q];
              else
                E = bdf.a0 * u[q] +
                    bdf.a1 * (vf[q] * u_old[q] + solid * u_s[q]) +
                    bdf.a2 * (vf[q] * u_older[q] + solid * u_s[q]);
              const double density =
                last_was_steady ? rho + rho_theta * solid : rho_theta;
              g[q] = (density * solid / last_time_step) * E;
            }
      };

      // The penalty acts on the discrete fluid through its rows,
      // R_k = int g phi_k, and so does the grain: its force is sum_k R_k and
      // its torque sum_k (x_k - c) x R_k with x_k the node (Q2 interpolates
      // rigid motions exactly, so this is the discrete dual of the grain's
      // rigid velocity). Taken point by point instead, the Theta-sized parts
      // that cancel within the rows of the solved system (against the
      // pressure, and the rigid rows' constraint reactions above, which act
      // at the nodes) act at other places and leave a Theta-sized couple
      // that spins a grain as soon as it changes velocity. Each grain gets
      // the rows of its own points.
      const unsigned int                   n_dofs = fe.n_dofs_per_cell();
      const Quadrature<dim>                nodes(fe.get_unit_support_points());
      FEValues<dim>       node_values(fe, nodes, update_quadrature_points);
      std::vector<int>    grains_here;
      std::vector<double> rows(n_dofs);
      for_each_covered_cell(
        update_values | update_quadrature_points | update_JxW_values,
        [&](const FEValues<dim>               &fe_values,
            const std::vector<double>         &vf,
            const std::vector<Tensor<1, dim>> &u_s,
            const std::vector<int>            &index) {
          penalty_density(fe_values, vf, u_s, index);
          node_values.reinit(fe_values.get_cell());
          grains_here.clear();
          for (unsigned int q = 0; q < vf.size(); ++q)
            if (index[q] >= 0 && vf[q] < 1 &&
                std::find(grains_here.begin(), grains_here.end(), index[q]) ==
                  grains_here.end())
              grains_here.push_back(index[q]);
          for (const int grain : grains_here)
            {
              std::fill(rows.begin(), rows.end(), 0.);
              for (unsigned int q = 0; q < vf.size(); ++q)
                if (index[q] == grain && vf[q] < 1)
                  for (unsigned int k = 0; k < n_dofs; ++k)
                    {
                      const unsigned int c =
                        fe.system_to_component_index(k).first;
                      if (c < dim)
                        rows[k] += g[q][c] * fe_values.shape_value(k, q) *
                                   fe_values.JxW(q);
                    }
              for (unsigned int k = 0; k < n_dofs; ++k)
                if (rows[k] != 0)
                  {
                    Tensor<1, dim> force;
                    force[fe.system_to_component_index(k).first] = rows[k];
                    f(grain, node_values.quadrature_point(k), force);
                  }
            }
        });
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::for_each_covered_cell(
      const UpdateFlags  flags,
      const std::function<void(const FEValues<dim> &,
                               const std::vector<double> &,
                               const std::vector<Tensor<1, dim>> &,
                               const std::vector<int> &)> &cell_action) const
    {
      const QGauss<dim>           quadrature(fe.degree + 1);
      FEValues<dim>               fe_values(fe, quadrature, flags);
      std::vector<Tensor<1, dim>> u_s;
      std::vector<double>         vf;
      std::vector<int>            index;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            evaluate_solids(
              *cell, fe_values.get_quadrature_points(), vf, u_s, index);
            for (unsigned int q = 0; q < vf.size(); ++q)
              if (index[q] >= 0 && vf[q] < 1)
                {
                  cell_action(fe_values, vf, u_s, index);
                  break;
                }
          }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::for_each_solid_stress_divergence(
      const std::function<void(const int,
                               const Point<dim> &,
                               const Tensor<1, dim> &)> &f) const
    {
      if (solid_field == nullptr)
        return;
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);
      std::vector<Tensor<1, dim>>      lap_u, grad_p;
      const double                     mu = fluid_parameters.viscosity;
      for_each_covered_cell(
        update_values | update_gradients | update_hessians |
          update_quadrature_points | update_JxW_values,
        [&](const FEValues<dim>               &fe_values,
            const std::vector<double>         &vf,
            const std::vector<Tensor<1, dim>> &,
            const std::vector<int>            &index) {
          lap_u.resize(vf.size());
          grad_p.resize(vf.size());
          fe_values[velocities].get_function_laplacians(solution, lap_u);
          fe_values[pressure].get_function_gradients(solution, grad_p);
          for (unsigned int q = 0; q < vf.size(); ++q)
            if (index[q] >= 0 && vf[q] < 1)
              f(index[q],
                fe_values.quadrature_point(q),
                (1. - vf[q]) * (mu * lap_u[q] - grad_p[q]) * fe_values.JxW(q));
        });
    }


    // Instantiated member by member: the class's other members are
    // defined in penalized_navier_stokes.cc and its sibling files.
    template void
    PenalizedNavierStokes<2>::compute_reactions(const Assembly     kind,
                                                const double       dt,
                                                const unsigned int bdf_order);
    template Tensor<1, 2>
    PenalizedNavierStokes<2>::pressure_face_force() const;
    template void
    PenalizedNavierStokes<2>::for_each_solid_reaction(
      const std::function<
        void(const int, const Point<2> &, const Tensor<1, 2> &)> &f) const;
    template void
    PenalizedNavierStokes<2>::for_each_covered_cell(
      const UpdateFlags                                    flags,
      const std::function<void(const FEValues<2> &,
                               const std::vector<double> &,
                               const std::vector<Tensor<1, 2>> &,
                               const std::vector<int> &)> &cell_action) const;
    template void
    PenalizedNavierStokes<2>::for_each_solid_stress_divergence(
      const std::function<
        void(const int, const Point<2> &, const Tensor<1, 2> &)> &f) const;
    template void
    PenalizedNavierStokes<3>::compute_reactions(const Assembly     kind,
                                                const double       dt,
                                                const unsigned int bdf_order);
    template Tensor<1, 3>
    PenalizedNavierStokes<3>::pressure_face_force() const;
    template void
    PenalizedNavierStokes<3>::for_each_solid_reaction(
      const std::function<
        void(const int, const Point<3> &, const Tensor<1, 3> &)> &f) const;
    template void
    PenalizedNavierStokes<3>::for_each_covered_cell(
      const UpdateFlags                                    flags,
      const std::function<void(const FEValues<3> &,
                               const std::vector<double> &,
                               const std::vector<Tensor<1, 3>> &,
                               const std::vector<int> &)> &cell_action) const;
    template void
    PenalizedNavierStokes<3>::for_each_solid_stress_divergence(
      const std::function<
        void(const int, const Point<3> &, const Tensor<1, 3> &)> &f) const;
  } // namespace fluid
} // namespace softsand
