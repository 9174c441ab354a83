// PenalizedNavierStokes: the penalized momentum equation assembled, rho*
// = rho (1 + Theta (1 - vf)) with the grains' rigid velocity, convection,
// BDF time terms and the pressure regions' traction faces.

#include <softsand/fluid/block_schur_preconditioner.h>
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
    double
    PenalizedNavierStokes<dim>::brinkman_coefficient(
      const double vf,
      const double penalty_time_step) const
    {
      const double solid = 1. - vf;
      return fluid_parameters.density *
             (1. + fluid_parameters.theta * solid) * solid / penalty_time_step;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::add_inflow_traction(
      const FEFaceValuesBase<dim> &face_values,
      const Assembly               kind,
      const unsigned int           bdf_order,
      FullMatrix<double>          &local_matrix) const
    {
      const FEValuesExtractors::Vector velocities(0);
      const unsigned int n_q = face_values.n_quadrature_points;
      std::vector<Tensor<1, dim>> w(n_q), w_older(n_q);
      // The advecting velocity of the volume term.
      if (kind == Assembly::transient)
        {
          face_values[velocities].get_function_values(old_solution, w);
          if (bdf_order != 1)
            {
              const BDFCoefficients c = bdf_coefficients(2, bdf_step_ratio);
              face_values[velocities].get_function_values(older_solution,
                                                          w_older);
              for (unsigned int q = 0; q < n_q; ++q)
                w[q] = c.e1 * w[q] + c.e2 * w_older[q];
            }
        }
      else
        face_values[velocities].get_function_values(solution, w);

      const double rho = fluid_parameters.density;
      const auto  &fe  = face_values.get_fe();
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const double w_n = w[q] * face_values.normal_vector(q);
          if (w_n >= 0)
            continue;
          const double weight = -0.5 * rho * w_n * face_values.JxW(q);
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            {
              const unsigned int ci = fe.system_to_component_index(i).first;
              if (ci == dim)
                continue;
              const double phi_i = face_values.shape_value(i, q);
              if (phi_i == 0)
                continue;
              for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
                if (fe.system_to_component_index(j).first == ci)
                  local_matrix(i, j) +=
                    weight * phi_i * face_values.shape_value(j, q);
            }
        }
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::relative_target_divergence(
      const FEValues<dim>                        &fe_values,
      const std::vector<types::global_dof_index> &dof_indices,
      const std::vector<unsigned int>            &component,
      const double                                h) const
    {
      // The cell's target field: a node's blended target; a hanging node's
      // parents' targets by their weights; a wall node its imposed value.
      // Nodes without one (free, or the free share of a hanging node) take
      // the cell's mean target, so that one grain translating past free
      // fluid or a refinement boundary is no squeeze.
      const unsigned int n = dof_indices.size();
      std::vector<double> value(n, 0.);
      std::vector<double> free_share(n, 0.);
      Tensor<1, dim>      sum;
      std::array<unsigned int, dim> count{};
      double largest = 0;
      for (unsigned int k = 0; k < n; ++k)
        if (component[k] < dim)
          {
            const auto i      = dof_indices[k];
            const auto target = limit_target.find(i);
            if (target != limit_target.end())
              {
                value[k] = target->second;
                sum[component[k]] += target->second;
                ++count[component[k]];
                largest = std::max(largest, std::abs(target->second));
                continue;
              }
            const auto hanging = hanging_rigid_parents.find(i);
            if (hanging != hanging_rigid_parents.end())
              {
                double weights = 0;
                for (const auto &[parent, weight] : hanging->second)
                  {
                    const auto t = limit_target.find(parent);
                    if (t == limit_target.end())
                      continue;
                    value[k] += weight * t->second;
                    weights += weight;
                  }
                free_share[k] = 1. - weights;
              }
            else if (const auto *entries = constraints.get_constraint_entries(i);
                     entries != nullptr && entries->empty())
              value[k] = constraints.get_inhomogeneity(i);
            else
              free_share[k] = 1.;
          }
      double divergence = 0, volume = 0;
      const unsigned int n_q = fe_values.n_quadrature_points;
      for (unsigned int q = 0; q < n_q; ++q)
        volume += fe_values.JxW(q);
      for (unsigned int k = 0; k < n; ++k)
        if (component[k] < dim)
          {
            const unsigned int c = component[k];
            const double t =
              value[k] + free_share[k] * (count[c] > 0 ? sum[c] / count[c] : 0.);
            if (t == 0)
              continue;
            // Taylor-Hood is primitive: phi_k has the one component c(k).
            double integral = 0;
            for (unsigned int q = 0; q < n_q; ++q)
              integral += fe_values.shape_grad(k, q)[c] * fe_values.JxW(q);
            divergence += t * integral;
          }
      // Below the cell's viscous velocity mu / (rho h) the targets are at
      // rest: a pack settled to 1e-10 m/s must not count as squeezing.
      const double scale = std::max(largest,
                                    fluid_parameters.viscosity /
                                      (fluid_parameters.density * h));
      return std::abs(divergence) * h / (volume * scale);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::assemble(const Assembly      kind,
                                         const double        dt,
                                         const unsigned int  bdf_order,
                                         const CellCallback *cell_callback,
                                         const CellFilter   *cell_filter)
    {
      TimerOutput::Scope t(timer,
                           cell_callback == nullptr ? "fluid: assemble" :
                                                      "fluid: reactions");
      if (cell_callback == nullptr)
        {
          // The pattern leaves out the rows and columns that constraints
          // fix. Moving grains fix other DoFs at nearly every step (74 %
          // of the velocity DoFs on the Hele-Shaw scene): their rows are
          // dropped again whenever the set changes (the preconditioner is
          // rebuilt then anyway). The first Newton step needs the entries
          // between velocity components; a matrix-free scene allocates the
          // matrix at its first matrix-based assembly.
          IndexSet fixed;
          bool     fixed_changed = false;
          if (moving_solids)
            {
              fixed = owned_constrained_dofs();
              fixed_changed =
                Utilities::MPI::min((fixed.size() ==
                                       pattern_constraints.size() &&
                                     fixed == pattern_constraints) ?
                                      1 :
                                      0,
                                    mpi_communicator) == 0;
            }
          if (fixed_changed || system_matrix.n_block_rows() == 0 ||
              (couples_velocity_components(kind) &&
               !velocity_components_coupled))
            {
              velocity_components_coupled =
                velocity_components_coupled ||
                couples_velocity_components(kind);
              reinit_system_matrix();
              pattern_constraints = fixed;
            }
        }
      if (cell_callback == nullptr)
        {
          system_matrix           = 0;
          pressure_mass_matrix    = 0;
          pressure_laplace_matrix = 0;
          system_rhs              = 0;
        }

      const double rho = fluid_parameters.density;
      const double mu  = fluid_parameters.viscosity;
      const SolverParameters::Schur schur = solver_parameters.schur;
      // Grad-div: gamma (div v, div u) penalizes the discrete divergence, so
      // that the Schur complement of the convective block approaches
      // -(mu + gamma)^-1 M_p (step-57); without it the mass approximation
      // misses convection and FGMRES stalls at Re ~ 50.
      // In coarse cells at a high cell Reynolds number the Schur
      // complement is ~ (rho |u| h)^-1 M_p: gamma grows there with the
      // cell part c rho |w| h.
      const double grad_div = solver_parameters.grad_div;
      const double grad_div_cell_factor =
        solver_parameters.grad_div_cell_factor;

      const double beta_floor = viscous_beta_floor();

      const QGauss<dim>     quadrature(fe.degree + 1);
      const QGauss<dim - 1> face_quadrature(fe.degree + 1);
      FEValues<dim>         fe_values(fe,
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
      FEFaceValues<dim>     fe_face_values(fe,
                                       face_quadrature,
                                       update_values | update_normal_vectors |
                                         update_JxW_values);
      FESubfaceValues<dim>  fe_subface_values(fe,
                                             face_quadrature,
                                             update_values |
                                               update_normal_vectors |
                                               update_JxW_values);
      const unsigned int dofs_per_cell = fe.n_dofs_per_cell();
      const unsigned int n_q           = quadrature.size();
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);

      FullMatrix<double> local_matrix(dofs_per_cell, dofs_per_cell);
      FullMatrix<double> local_mass(dofs_per_cell, dofs_per_cell);
      FullMatrix<double> local_laplace(dofs_per_cell, dofs_per_cell);
      Vector<double>     local_rhs(dofs_per_cell);
      std::vector<types::global_dof_index> dof_indices(dofs_per_cell);

      std::vector<double>         shape_value(dofs_per_cell);
      std::vector<Tensor<1, dim>> shape_grad(dofs_per_cell);
      std::vector<unsigned int>   component(dofs_per_cell);
      std::array<std::vector<unsigned int>, dim + 1> dofs_of_component;
      for (unsigned int k = 0; k < dofs_per_cell; ++k)
        {
          component[k] = fe.system_to_component_index(k).first;
          dofs_of_component[component[k]].push_back(k);
        }
      // The velocity components share one scalar Q2 element: outside
      // Newton's method their diagonal blocks are one scalar block,
      // computed once per cell and copied to each component (the hot loop
      // of the assembly, 3x less work). velocity_dof[c][a]: the cell DoF
      // of component c for scalar shape function a.
      const unsigned int n_scalar = dofs_of_component[0].size();
      std::array<std::vector<unsigned int>, dim> velocity_dof;
      for (unsigned int c = 0; c < dim; ++c)
        velocity_dof[c].resize(n_scalar);
      for (unsigned int k = 0; k < dofs_per_cell; ++k)
        if (component[k] < dim)
          velocity_dof[component[k]][fe.system_to_component_index(k).second] =
            k;
      FullMatrix<double>          scalar_block(n_scalar, n_scalar);
      std::vector<double>         scalar_value(n_scalar), w_dot_grad(n_scalar);
      std::vector<Tensor<1, dim>> scalar_grad(n_scalar);
      const bool one_scalar_block = (kind != Assembly::steady_newton);

      std::vector<Tensor<1, dim>> u_current(n_q), u_old(n_q), u_older(n_q);
      std::vector<Tensor<2, dim>> grad_u_current(n_q), grad_u_old(n_q),
        grad_u_older(n_q);
      std::vector<double>         void_fraction(n_q, 1.);
      std::vector<Tensor<1, dim>> solid_velocity(n_q);
      std::vector<int>            solid_index(n_q, -1);
      Vector<double>              force_value(dim);

      const bool            first_order = (bdf_order == 1);
      const BDFCoefficients bdf =
        bdf_coefficients(first_order ? 1 : 2, bdf_step_ratio);
      const bool smooth = smooth_solid_pressure();

      // The rows a callback reads (all without a filter), and those of
      // the scalar velocity block.
      std::vector<bool> rows(dofs_per_cell, true);
      std::vector<bool> scalar_rows(n_scalar, true);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            if (cell_filter != nullptr)
              {
                std::fill(rows.begin(), rows.end(), true);
                if (!(*cell_filter)(cell, rows))
                  continue;
                for (unsigned int a = 0; a < n_scalar; ++a)
                  {
                    scalar_rows[a] = false;
                    for (unsigned int c = 0; c < dim; ++c)
                      scalar_rows[a] =
                        scalar_rows[a] || rows[velocity_dof[c][a]];
                  }
              }
            fe_values.reinit(cell);
            local_matrix  = 0;
            local_mass    = 0;
            local_laplace = 0;
            local_rhs     = 0;
            scalar_block  = 0;

            // Rigid nodes, penalization limit: the grain acts through
            // constraints only.
            if (solid_field != nullptr && !constrains_solids())
              evaluate_solids(
                *cell,
                fe_values.get_quadrature_points(),
                void_fraction,
                solid_velocity,
                solid_index);
            else
              void_fraction.assign(n_q, 1.);
            // The hybrid model's porous cells: a drag instead of grains.
            const PorousCell<dim> porous = porous_cell(*cell);

            if (kind == Assembly::steady_picard ||
                kind == Assembly::steady_newton)
              {
                fe_values[velocities].get_function_values(solution, u_current);
                fe_values[velocities].get_function_gradients(solution,
                                                             grad_u_current);
              }
            if (kind == Assembly::transient)
              {
                fe_values[velocities].get_function_values(old_solution, u_old);
                fe_values[velocities].get_function_gradients(old_solution,
                                                             grad_u_old);
                if (!first_order)
                  {
                    fe_values[velocities].get_function_values(older_solution,
                                                              u_older);
                    fe_values[velocities].get_function_gradients(
                      older_solution, grad_u_older);
                  }
              }

            const double h = cell->diameter() / std::sqrt(double(dim));
            // A pressure region (inlet reservoir): only the pressure term
            // -(p, div v) with the region's fixed pressure, which is the
            // traction condition on the region's surface (PressureRegion).
            const bool reservoir =
              boundary_conditions.has_pressure_regions() &&
              boundary_conditions.pressure_region(cell->center()) != nullptr;

            // Rigid nodes: the pressure of a cut cell acts only on the free
            // velocity nodes, so the Schur complement there is smaller than
            // the viscous mass matrix by about the free fraction: scale the
            // approximation alike.
            double free_fraction = 1;
            // Cells with few free velocity nodes leave pressure modes that
            // no free velocity sees; the pressure Laplacian (weight
            // solid_smoothing, growing with the imposed fraction) makes
            // them continue the fluid's pressure smoothly.
            double solid_smoothing = 0;
            if (!rigid_dof_grain.empty())
              {
                cell->get_dof_indices(dof_indices);
                unsigned int n_velocity = 0, n_rigid = 0, n_fixed = 0;
                for (unsigned int k = 0; k < dofs_per_cell; ++k)
                  if (component[k] < dim)
                    {
                      ++n_velocity;
                      n_rigid += rigid_dof_grain.count(dof_indices[k]);
                      if (smooth)
                        n_fixed += is_fixed_velocity(dof_indices[k]);
                    }
                std::tie(free_fraction, solid_smoothing) =
                  rigid_cell_weights(n_velocity, n_rigid, n_fixed, h);
                // Penalization limit: where the blended targets squeeze
                // or part the fluid, the constraints contradict
                // continuity; relax it there (FluidParameters).
                if (solid_smoothing > 0)
                  solid_smoothing *=
                    squeeze_factor(fe_values, dof_indices, component, h);
              }

            for (unsigned int q = 0; q < n_q; ++q)
              {
                const double JxW = fe_values.JxW(q);
                // Taylor-Hood is primitive: each shape function has one
                // nonzero component, so store scalars and skip the zero
                // couplings below (about 3x less work in 3D).
                for (unsigned int k = 0; k < dofs_per_cell; ++k)
                  {
                    shape_value[k] = fe_values.shape_value(k, q);
                    shape_grad[k]  = fe_values.shape_grad(k, q);
                  }

                const double vf    = void_fraction[q];
                const double solid = 1. - vf;

                // Zeroth-order coefficient (mass or Brinkman) and the vector
                // it multiplies on the right-hand side.
                double         beta = 0;
                Tensor<1, dim> beta_rhs;
                // Advecting velocity and its divergence (skew-symmetric
                // Temam term keeps the Oseen step energy-stable).
                Tensor<1, dim> w;
                double         div_w      = 0;
                bool           convection = false;
                bool           newton     = false;
                Tensor<2, dim> grad_w;

                if (kind == Assembly::transient)
                  {
                    const double rho_star =
                      rho * (1. + fluid_parameters.theta * solid);
                    const Tensor<1, dim> u_tilde_old =
                      vf * u_old[q] + solid * solid_velocity[q];
                    // BDF1: a2 = e2 = 0, so u_older (left at zero) drops out.
                    const Tensor<1, dim> u_tilde_older =
                      vf * u_older[q] + solid * solid_velocity[q];
                    beta     = bdf.a0 * rho_star / dt;
                    beta_rhs = -rho_star / dt *
                               (bdf.a1 * u_tilde_old + bdf.a2 * u_tilde_older);
                    w        = bdf.e1 * u_old[q] + bdf.e2 * u_older[q];
                    div_w    = bdf.e1 * trace(grad_u_old[q]) +
                            bdf.e2 * trace(grad_u_older[q]);
                    convection = true;
                  }
                else
                  {
                    beta     = brinkman_coefficient(vf, dt);
                    beta_rhs = beta * solid_velocity[q];
                    if (kind != Assembly::steady_stokes)
                      {
                        w          = u_current[q];
                        grad_w     = grad_u_current[q];
                        convection = true;
                        newton     = (kind == Assembly::steady_newton);
                        if (pseudo_time_cfl > 0)
                          {
                            // Pseudo time: rho |w| / (cfl h) (u - u_k).
                            const double pseudo =
                              rho * w.norm() / (pseudo_time_cfl * h);
                            beta += pseudo;
                            beta_rhs += pseudo * w;
                          }
                      }
                  }

                if (porous.porous)
                  {
                    const Tensor<1, dim> grain_flux = porous.grain_flux();
                    const double drag = porous.drag(mu, rho, w - grain_flux);
                    beta += drag;
                    beta_rhs += drag * grain_flux;
                  }

                body_force->vector_value(fe_values.quadrature_point(q),
                                         force_value);
                Tensor<1, dim> f;
                for (unsigned int d = 0; d < dim; ++d)
                  f[d] = force_value[d];
                if (newton)
                  f += rho * (grad_w * w); // rho (u_k . grad) u_k

                const double gamma =
                  grad_div + grad_div_cell_factor * rho * w.norm() * h;

                // Schur complement approximation coefficients (per point).
                double mass_weight = free_fraction / (mu + gamma);
                if (schur == SolverParameters::Schur::weighted_mass)
                  mass_weight = free_fraction / (mu + gamma + beta * h * h);
                const double laplace_weight =
                  (schur == SolverParameters::Schur::cahouet_chabard) ?
                    1. / (beta + beta_floor) :
                    0.;

                // Picard iterates in Temam's form as the transient model
                // does: where the last iterate is far from divergence free
                // (rigid-node cells) the plain form is not energy-stable,
                // and Oseen iterations at pore Reynolds numbers of 100
                // diverged without it (doc/notes/solver_study.md, "Oseen").
                if (kind == Assembly::steady_picard)
                  div_w = trace(grad_w);
                const double temam =
                  (convection && kind != Assembly::steady_newton) ?
                    0.5 * rho * div_w :
                    0.;
                // Loops over the dofs of each component: Taylor-Hood is
                // primitive, so only the couplings below are nonzero.
                const auto &pressure_dofs = dofs_of_component[dim];
                const bool  cross_components = newton || gamma != 0;
                if (one_scalar_block && !reservoir)
                  {
                    const double zeroth = beta + temam;
                    for (unsigned int a = 0; a < n_scalar; ++a)
                      {
                        const unsigned int k = velocity_dof[0][a];
                        scalar_value[a]      = shape_value[k];
                        scalar_grad[a]       = shape_grad[k];
                        w_dot_grad[a] = convection ? w * shape_grad[k] : 0.;
                      }
                    for (unsigned int a = 0; a < n_scalar; ++a)
                      {
                        if (!scalar_rows[a])
                          continue;
                        const double phi_a    = scalar_value[a];
                        const double advect_a = convection ? rho * phi_a : 0.;
                        double      *row      = &scalar_block(a, 0);
                        for (unsigned int b = 0; b < n_scalar; ++b)
                          {
                            double v = mu * (scalar_grad[a] * scalar_grad[b]) +
                                       zeroth * phi_a * scalar_value[b];
                            if (convection)
                              v += advect_a * w_dot_grad[b];
                            row[b] += v * JxW;
                          }
                      }
                  }
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    if (!rows[i])
                      continue;
                    const unsigned int ci  = component[i];
                    const double       phi = shape_value[i];
                    if (ci == dim) // pressure test function
                      {
                        // -(q, div u): the transpose of the velocity rows'
                        // -(div v, p), copied after the quadrature loop.
                        for (const unsigned int j : pressure_dofs)
                          {
                            const double grad_grad =
                              shape_grad[i] * shape_grad[j];
                            if (solid_smoothing > 0)
                              {
                                const double smoothing =
                                  solid_smoothing * grad_grad * JxW;
                                local_matrix(i, j) -= smoothing;
                                local_mass(i, j) += smoothing;
                              }
                            local_mass(i, j) +=
                              mass_weight * phi * shape_value[j] * JxW;
                            if (laplace_weight != 0)
                              local_laplace(i, j) +=
                                laplace_weight * grad_grad * JxW;
                          }
                        continue;
                      }
                    // Velocity test function in component ci.
                    const Tensor<1, dim> &grad_i = shape_grad[i];
                    for (const unsigned int j : pressure_dofs)
                      local_matrix(i, j) -= grad_i[ci] * shape_value[j] * JxW;
                    if (!reservoir)
                      {
                        const double advect_i = convection ? rho * phi : 0.;
                        // Newton: rho (u . grad) w, its diagonal part here.
                        const double zeroth =
                          beta + temam + (newton ? rho * grad_w[ci][ci] : 0.);
                        if (!one_scalar_block)
                          for (const unsigned int j : dofs_of_component[ci])
                            {
                              double a = mu * (grad_i * shape_grad[j]) +
                                         zeroth * phi * shape_value[j];
                              if (convection)
                                a += advect_i * (w * shape_grad[j]);
                              local_matrix(i, j) += a * JxW;
                            }
                        if (cross_components)
                          for (unsigned int cj = 0; cj < dim; ++cj)
                            for (const unsigned int j : dofs_of_component[cj])
                              {
                                double a = gamma * grad_i[ci] * shape_grad[j][cj];
                                if (newton && cj != ci)
                                  a += advect_i * grad_w[ci][cj] * shape_value[j];
                                local_matrix(i, j) += a * JxW;
                              }
                        local_rhs(i) += (f[ci] + beta_rhs[ci]) * phi * JxW;
                      }
                  }
              }

            if (one_scalar_block && !reservoir)
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int a = 0; a < n_scalar; ++a)
                  if (rows[velocity_dof[c][a]])
                    for (unsigned int b = 0; b < n_scalar; ++b)
                      local_matrix(velocity_dof[c][a], velocity_dof[c][b]) +=
                        scalar_block(a, b);
            for (const unsigned int i : dofs_of_component[dim])
              if (rows[i])
                for (unsigned int cj = 0; cj < dim; ++cj)
                  for (const unsigned int j : dofs_of_component[cj])
                    local_matrix(i, j) = local_matrix(j, i);

            // Convection through a traction surface (pressure faces, the
            // surface of a pressure region): the directional do-nothing
            // condition mu du/dn - p n = -p_b n + rho/2 (w . n)_- u, which
            // is Bernoulli's p + rho/2 u_n^2 = p_b where fluid enters from
            // a reservoir at rest; without it inflow brings in kinetic
            // energy that the Galerkin convection term cannot carry, and
            // Oseen iterations diverge.
            if (kind != Assembly::steady_stokes && !reservoir)
              for (const unsigned int f : cell->face_indices())
                {
                  const auto face = cell->face(f);
                  if (face->at_boundary())
                    {
                      if (boundary_conditions.face(face->boundary_id()).type ==
                          BoundaryConditions<dim>::Type::pressure)
                        {
                          fe_face_values.reinit(cell, f);
                          add_inflow_traction(fe_face_values, kind, bdf_order,
                                              local_matrix);
                        }
                    }
                  else if (boundary_conditions.has_pressure_regions())
                    {
                      if (face->has_children())
                        {
                          for (unsigned int sf = 0; sf < face->n_children(); ++sf)
                            if (boundary_conditions.pressure_region(
                                  cell->neighbor_child_on_subface(f, sf)
                                    ->center()) != nullptr)
                              {
                                fe_subface_values.reinit(cell, f, sf);
                                add_inflow_traction(fe_subface_values, kind,
                                                    bdf_order, local_matrix);
                              }
                        }
                      else if (boundary_conditions.pressure_region(
                                 cell->neighbor(f)->center()) != nullptr)
                        {
                          fe_face_values.reinit(cell, f);
                          add_inflow_traction(fe_face_values, kind, bdf_order,
                                              local_matrix);
                        }
                    }
                }

            // Pressure faces: do-nothing condition mu du/dn - p n = -p_b n.
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() &&
                  boundary_conditions.face(face->boundary_id()).type ==
                    BoundaryConditions<dim>::Type::pressure)
                {
                  fe_face_values.reinit(cell, face);
                  const double p_b =
                    boundary_conditions.face(face->boundary_id()).pressure;
                  for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      local_rhs(i) -=
                        p_b *
                        (fe_face_values[velocities].value(i, q) *
                         fe_face_values.normal_vector(q)) *
                        fe_face_values.JxW(q);
                  // Weak p = 0 in the pressure Laplacian of the Schur
                  // approximation: the Schur complement sees a Dirichlet
                  // condition where the traction is prescribed.
                  if (schur == SolverParameters::Schur::cahouet_chabard)
                    {
                      const double penalty = 1. / (beta_floor * h);
                      for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                        for (unsigned int i = 0; i < dofs_per_cell; ++i)
                          for (unsigned int j = 0; j < dofs_per_cell; ++j)
                            local_laplace(i, j) +=
                              penalty *
                              fe_face_values[pressure].value(i, q) *
                              fe_face_values[pressure].value(j, q) *
                              fe_face_values.JxW(q);
                    }
                }

            cell->get_dof_indices(dof_indices);
            if (cell_callback != nullptr)
              {
                (*cell_callback)(cell, local_matrix, local_rhs, dof_indices);
                continue;
              }
            constraints.distribute_local_to_global(
              local_matrix, local_rhs, dof_indices, system_matrix, system_rhs);
            if (schur != SolverParameters::Schur::least_squares_commutator)
              constraints.distribute_local_to_global(local_mass,
                                                     dof_indices,
                                                     pressure_mass_matrix);
            if (schur == SolverParameters::Schur::cahouet_chabard)
              constraints.distribute_local_to_global(local_laplace,
                                                     dof_indices,
                                                     pressure_laplace_matrix);
          }

      if (cell_callback != nullptr)
        return;
      system_matrix.compress(VectorOperation::add);
      pressure_mass_matrix.compress(VectorOperation::add);
      pressure_laplace_matrix.compress(VectorOperation::add);
      system_rhs.compress(VectorOperation::add);
    }


    // Instantiated member by member: the class's other members are
    // defined in penalized_navier_stokes.cc and its sibling files.
    template double
    PenalizedNavierStokes<2>::brinkman_coefficient(
      const double vf,
      const double penalty_time_step) const;
    template void
    PenalizedNavierStokes<2>::add_inflow_traction(
      const FEFaceValuesBase<2> &face_values,
      const Assembly             kind,
      const unsigned int         bdf_order,
      FullMatrix<double>        &local_matrix) const;
    template void
    PenalizedNavierStokes<2>::assemble(const Assembly      kind,
                                       const double        dt,
                                       const unsigned int  bdf_order,
                                       const CellCallback *cell_callback,
                                       const CellFilter   *cell_filter);
    template double
    PenalizedNavierStokes<3>::brinkman_coefficient(
      const double vf,
      const double penalty_time_step) const;
    template void
    PenalizedNavierStokes<3>::add_inflow_traction(
      const FEFaceValuesBase<3> &face_values,
      const Assembly             kind,
      const unsigned int         bdf_order,
      FullMatrix<double>        &local_matrix) const;
    template void
    PenalizedNavierStokes<3>::assemble(const Assembly      kind,
                                       const double        dt,
                                       const unsigned int  bdf_order,
                                       const CellCallback *cell_callback,
                                       const CellFilter   *cell_filter);
  } // namespace fluid
} // namespace softsand
