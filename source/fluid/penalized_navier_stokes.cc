#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/penalization_limit.h>
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
    namespace
    {
      /// Sparsity of the blocks that @p coupling couples, from
      /// @p constraints, distributed over the locally relevant rows.
      template <int dim>
      BlockDynamicSparsityPattern
      make_block_pattern(const DoFHandler<dim>              &dof_handler,
                         const Table<2, DoFTools::Coupling> &coupling,
                         const AffineConstraints<double>    &constraints,
                         const std::vector<IndexSet> &relevant_partitioning,
                         const bool                   moving_solids)
      {
        const IndexSet &owned = dof_handler.locally_owned_dofs();
        const IndexSet  relevant =
          DoFTools::extract_locally_relevant_dofs(dof_handler);
        BlockDynamicSparsityPattern dsp(relevant_partitioning);
        DoFTools::make_sparsity_pattern(
          dof_handler, coupling, dsp, constraints, false);
        // Moving solids constrain nodes that this pattern saw free (velocity
        // nodes; pressure nodes they enclose, pinned to p = 0): those rows
        // need a diagonal that a block without self-coupling lacks. Every
        // locally relevant row: a rank assembling a cell whose constrained
        // node another rank owns writes that diagonal too (a grain on a
        // rank boundary).
        if (moving_solids)
          for (const auto i : relevant)
            dsp.add(i, i);
        SparsityTools::distribute_sparsity_pattern(
          dsp, owned, dof_handler.get_communicator(), relevant);
        return dsp;
      }
    } // namespace


    template <int dim>
    PenalizedNavierStokes<dim>::PenalizedNavierStokes(
      parallel::distributed::Triangulation<dim> &tria,
      const FluidParameters                     &fluid_parameters,
      const SolverParameters                    &solver_parameters,
      const BoundaryConditions<dim>             &boundary_conditions,
      ConditionalOStream                        &pcout,
      TimerOutput                               &timer)
        : mpi_communicator(tria.get_communicator())
        , triangulation(tria)
        , fluid_parameters(fluid_parameters)
        , solver_parameters(solver_parameters)
        , boundary_conditions(boundary_conditions)
        , pcout(pcout)
        , timer(timer)
        , fe(FE_Q<dim>(2), dim, FE_Q<dim>(1), 1)
        , dof_handler(tria)
        , fe_velocity(FE_Q<dim>(2), dim)
        , fe_pressure(1)
        , dof_handler_velocity(tria)
        , dof_handler_pressure(tria)
    {
      // The matrix-free operators know rigid nodes and the penalty, not the
      // blended constraints of the penalization limit.
      if (fluid_parameters.solid_model ==
          FluidParameters::SolidModel::penalization_limit)
        {
          if (solver_parameters.transient_solver ==
              SolverParameters::LinearSolver::matrix_free)
            base::throw_invalid_parameter(
              "fluid solver/transient solver",
              "matrix free",
              "fluid/solid model = penalization limit needs 'matrix based'");
          if (solver_parameters.linear_solver ==
              SolverParameters::LinearSolver::matrix_free)
            base::throw_invalid_parameter(
              "fluid solver/linear solver",
              "matrix free",
              "fluid/solid model = penalization limit needs 'matrix based'");
        }
      body_force = std::make_unique<FunctionParser<dim>>(dim);
      std::string expr = fluid_parameters.body_force;
      // Accept a 3-component default in 2D by dropping the z component.
      auto parts = Utilities::split_string_list(expr, ';');
      if (dim == 2 && parts.size() == 3)
        expr = parts[0] + ";" + parts[1];
      try
        {
          body_force->initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                                 expr,
                                 base::function_constants(),
                                 true);
          Vector<double> value(dim);
          body_force->vector_value(Point<dim>(), value);
        }
      catch (...)
        {
          AssertThrow(false,
                      ExcMessage("Parameter <fluid/body force> = <" +
                                 fluid_parameters.body_force +
                                 "> is invalid: give " + std::to_string(dim) +
                                 " expressions in x, y, z, t separated by "
                                 "';'."));
        }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_solid_field(const SolidField<dim> *solids)
    {
      solid_field = solids;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_moving_solids(const bool moving)
    {
      moving_solids = moving;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::find_velocity_wall_vertices()
    {
      velocity_wall_vertex.assign(triangulation.n_vertices(), false);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (!cell->is_artificial())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() <
                  boundary_conditions.n_boundary_ids() &&
                boundary_conditions.imposes_velocity(
                  cell->face(f)->boundary_id()))
              for (const auto v : cell->face(f)->vertex_indices())
                velocity_wall_vertex[cell->face(f)->vertex_index(v)] = true;
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::is_free_contact_cell(
      const CellAccessor<dim, dim> &cell) const
    {
      if (!frees_contact_cells())
        return false;
      for (const auto v : cell.vertex_indices())
        if (cell.vertex_index(v) < velocity_wall_vertex.size() &&
            velocity_wall_vertex[cell.vertex_index(v)])
          return true;
      return solid_field->n_solids_near(cell, cell.minimum_vertex_distance()) >=
             2;
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::frees_contact_cells() const
    {
      using F = FluidParameters::FreeContactCells;
      return solid_field != nullptr &&
             (fluid_parameters.free_contact_cells == F::yes ||
              (fluid_parameters.free_contact_cells == F::automatic &&
               moving_solids && !last_was_steady));
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::freed_solid_fraction() const
    {
      // Most scenes free nothing: no pass over the mesh for them.
      if (!frees_contact_cells())
        return 0.;
      const QGauss<dim>           quadrature(fe.degree + 1);
      FEValues<dim>               fe_values(fe,
                              quadrature,
                              update_quadrature_points | update_JxW_values);
      std::vector<double>         vf;
      std::vector<Tensor<1, dim>> u_s;
      std::vector<int>            grain;
      double                      solid = 0, freed = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            solid_field->evaluate(
              *cell, fe_values.get_quadrature_points(), vf, u_s, grain);
            double cell_solid = 0;
            for (const auto q : fe_values.quadrature_point_indices())
              cell_solid += (1. - vf[q]) * fe_values.JxW(q);
            solid += cell_solid;
            if (cell_solid > 0 && is_free_contact_cell(*cell))
              freed += cell_solid;
          }
      solid = Utilities::MPI::sum(solid, mpi_communicator);
      freed = Utilities::MPI::sum(freed, mpi_communicator);
      return solid > 0 ? freed / solid : 0.;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::evaluate_solids(
      const CellAccessor<dim, dim> &cell,
      const std::vector<Point<dim>>  &points,
      std::vector<double>            &void_fraction,
      std::vector<Tensor<1, dim>>    &solid_velocity,
      std::vector<int>               &solid_index) const
    {
      solid_field->evaluate(
        cell, points, void_fraction, solid_velocity, solid_index);
      if (std::any_of(solid_index.begin(),
                      solid_index.end(),
                      [](const int g) { return g >= 0; }) &&
          is_free_contact_cell(cell))
        {
          void_fraction.assign(points.size(), 1.);
          solid_velocity.assign(points.size(), Tensor<1, dim>());
          solid_index.assign(points.size(), -1);
        }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::prepare_for_coarsening_and_refinement()
    {
      solution_transfer = std::make_unique<
        parallel::distributed::SolutionTransfer<dim, BlockVector>>(dof_handler);
      solution_transfer->prepare_for_coarsening_and_refinement(
        std::vector<const BlockVector *>{&solution,
                                         &old_solution,
                                         &older_solution});
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_solutions(
      const std::vector<BlockVector *> &values)
    {
      // Hanging nodes of the new mesh take their parents' values; the
      // other constraints (boundary, solids) are imposed by the next solve.
      AffineConstraints<double> hanging(
        DoFTools::extract_locally_relevant_dofs(dof_handler));
      DoFTools::make_hanging_node_constraints(dof_handler, hanging);
      hanging.close();
      BlockVector *targets[3] = {&solution, &old_solution, &older_solution};
      for (unsigned int k = 0; k < 3; ++k)
        {
          hanging.distribute(*values[k]);
          *targets[k] = *values[k];
        }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::transfer_after_coarsening_and_refinement()
    {
      AssertThrow(solution_transfer != nullptr,
                  ExcMessage("transfer_after_coarsening_and_refinement() "
                             "without prepare_for_coarsening_and_refinement()"));
      const unsigned int steps = steps_since_start;
      setup_dofs();
      steps_since_start = steps;
      std::vector<BlockVector> values(
        3, BlockVector(owned_partitioning, mpi_communicator));
      std::vector<BlockVector *> pointers = {&values[0], &values[1], &values[2]};
      solution_transfer->interpolate(pointers);
      solution_transfer.reset();
      set_solutions(pointers);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::prepare_for_serialization()
    {
      solution_transfer = std::make_unique<
        parallel::distributed::SolutionTransfer<dim, BlockVector>>(dof_handler);
      solution_transfer->prepare_for_serialization(
        std::vector<const BlockVector *>{&solution,
                                         &old_solution,
                                         &older_solution});
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::deserialize(const unsigned int steps_done,
                                            const double       previous_step)
    {
      setup_dofs();
      steps_since_start       = steps_done;
      previous_transient_step = previous_step;
      std::vector<BlockVector> values(
        3, BlockVector(owned_partitioning, mpi_communicator));
      std::vector<BlockVector *> pointers = {&values[0], &values[1], &values[2]};
      parallel::distributed::SolutionTransfer<dim, BlockVector> transfer(
        dof_handler);
      transfer.deserialize(pointers);
      solution_transfer.reset();
      set_solutions(pointers);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_time(const double t)
    {
      time = t;
      body_force->set_time(t);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::make_constraints(const bool with_solids)
    {
      const IndexSet relevant =
        DoFTools::extract_locally_relevant_dofs(dof_handler);
      constraints.clear();
      constraints.reinit(relevant);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      boundary_conditions.make_velocity_constraints(dof_handler,
                                                    constraints,
                                                    time);
      make_pressure_region_constraints(dof_handler,
                                       boundary_conditions.inlet_region(),
                                       boundary_conditions.perimeter_region(),
                                       constraints);
      rigid_dof_grain.clear();
      rigid_dof_shares.clear();
      hanging_rigid_parents.clear();
      if (with_solids &&
          (rigid_nodes() || constrained_interiors() || penalization_limit()))
        {
          if (penalization_limit())
            add_penalization_limit_constraints();
          else
            add_solid_constraints(dof_handler,
                                  constraints,
                                  rigid_nodes() ? rigid_node_inflation() : 0.,
                                  &rigid_dof_grain);

          // Hanging nodes whose parents are rigid carry part of the grain's
          // reaction; close() below resolves those parents away, so keep
          // the original weights.
          for (const auto &line : constraints.get_lines())
            for (const auto &[parent, weight] : line.entries)
              if (rigid_dof_grain.count(parent))
                hanging_rigid_parents[line.index].emplace_back(parent, weight);

          // Smoothed (assemble()): every pressure node is determined.
          if (!smooth_solid_pressure())
            pin_undetermined_solid_pressures();
        }
      constraints.close();
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::pin_undetermined_solid_pressures()
    {
      // Only locally active dofs: their cells are all owned or ghost.
      // Pinning them spares FGMRES one null vector per node.
      const IndexSet active = DoFTools::extract_locally_active_dofs(dof_handler);
      std::set<types::global_dof_index> free_pressure, solid_pressure;
      std::vector<types::global_dof_index> dof_indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(dof_indices);
            bool solid_cell = true;
            for (unsigned int k = 0; k < dof_indices.size() && solid_cell; ++k)
              if (fe.system_to_component_index(k).first < dim)
                solid_cell = is_fixed_velocity(dof_indices[k]);
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              if (fe.system_to_component_index(k).first == dim)
                (solid_cell ? solid_pressure : free_pressure)
                  .insert(dof_indices[k]);
          }
      for (const auto i : solid_pressure)
        if (free_pressure.count(i) == 0 && active.is_element(i) &&
            !constraints.is_constrained(i))
          constraints.add_line(i);
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::is_fixed_velocity(
      const types::global_dof_index i) const
    {
      if (rigid_dof_grain.count(i))
        return true;
      const auto *entries = constraints.get_constraint_entries(i);
      if (entries == nullptr)
        return false;
      const auto hanging = hanging_rigid_parents.find(i);
      return entries->empty() || (hanging != hanging_rigid_parents.end() &&
                                  hanging->second.size() == entries->size());
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::add_penalization_limit_constraints()
    {
      // The Theta -> infinity limit of rho* (u^{n+1} - u~) / dt with
      // u~ = vf u^n + (1 - vf) u_s is u^{n+1} = u~ (BDF1, the paper's
      // update), taken per node with one blended u_s (penalization_limit.h);
      // its fixed point, in steady solves, is u = u_s. setup_dofs() asks
      // before the solutions have the new mesh's layout: only which DoFs
      // are fixed matters there.
      const bool transient =
        !last_was_steady && old_solution.size() == dof_handler.n_dofs();
      const auto nodes = penalization_limit_nodes<dim>(
        dof_handler,
        [this](const CellAccessor<dim, dim>  &cell,
               const std::vector<Point<dim>> &points,
               std::vector<double>           &vf,
               std::vector<Tensor<1, dim>>   &u_s,
               std::vector<int>              &grain) {
          solid_field->evaluate(cell, points, vf, u_s, grain);
        },
        [this](const CellAccessor<dim, dim> &cell) {
          return is_free_contact_cell(cell);
        });
      // Boundary, hanging-node and pressure-region constraints keep
      // priority.
      for (const auto &[i, node] : nodes)
        if (!constraints.is_constrained(i) && constraints.can_store_line(i))
          {
            const double old_velocity = transient ? old_solution(i) : 0.;
            const double value =
              transient ? node.void_fraction * old_velocity +
                            (1. - node.void_fraction) * node.target :
                          node.target;
            constraints.add_line(i);
            constraints.set_inhomogeneity(i, value);
            rigid_dof_grain[i] = node.grain_shares.front().first;
            if (node.grain_shares.size() > 1)
              rigid_dof_shares[i] = node.grain_shares;
          }
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::rigid_node_inflation() const
    {
      // One offset for the whole mesh (grain surfaces sit in the finest
      // cells): a per-cell spacing would let a coarse neighbour claim nodes
      // that the fine cells sharing them leave free. Q2 nodes are half a
      // cell edge apart.
      double finest = std::numeric_limits<double>::max();
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          finest = std::min(finest, cell->minimum_vertex_distance());
      finest = Utilities::MPI::min(finest, mpi_communicator);
      return fluid_parameters.rigid_node_offset * finest / fe.degree;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::add_solid_constraints(
      const DoFHandler<dim>                  &dof,
      AffineConstraints<double>              &constraints,
      const double                            inflation,
      std::unordered_map<types::global_dof_index, int> *grain_of_dof) const
    {
      // Theta -> infinity: nodes inside a grain move with it (rigid nodes:
      // every node inside; penalization: the nodes of cells wholly inside
      // one grain, so that the penalty stays in cut cells). Boundary and
      // hanging-node constraints keep priority. Ghost cells are visited too,
      // so that ranks agree on shared dofs.
      const FiniteElement<dim> &element = dof.get_fe();
      const Quadrature<dim>     nodes(element.get_unit_support_points());
      FEValues<dim> fe_values(element, nodes, update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices(
        element.n_dofs_per_cell());
      std::vector<double>         vf;
      std::vector<Tensor<1, dim>> u_s;
      std::vector<int>            grain;
      // Nodes of contact cells stay free (is_free_contact_cell()).
      std::set<types::global_dof_index> contact_dofs;
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial() && is_free_contact_cell(*cell))
          {
            cell->get_dof_indices(dof_indices);
            contact_dofs.insert(dof_indices.begin(), dof_indices.end());
          }
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial())
          {
            fe_values.reinit(cell);
            solid_field->evaluate_exact(*cell,
                                        fe_values.get_quadrature_points(),
                                        vf,
                                        u_s,
                                        grain,
                                        inflation);
            cell->get_dof_indices(dof_indices);
            // A box whose nodes all lie in one sphere lies in it.
            if (!rigid_nodes() &&
                !std::all_of(grain.begin(), grain.end(), [&](const int g) {
                  return g >= 0 && g == grain[0];
                }))
              continue;
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              {
                const unsigned int c =
                  element.system_to_component_index(k).first;
                const auto i = dof_indices[k];
                if (c >= dim || grain[k] < 0 || constraints.is_constrained(i) ||
                    !constraints.can_store_line(i) || contact_dofs.count(i))
                  continue;
                constraints.add_line(i);
                if (grain_of_dof != nullptr)
                  {
                    constraints.set_inhomogeneity(i, u_s[k][c]);
                    (*grain_of_dof)[i] = grain[k];
                  }
              }
          }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::setup_dofs()
    {
      TimerOutput::Scope t(timer, "fluid: setup dofs");
      find_velocity_wall_vertices();
      dof_handler.distribute_dofs(fe);
      std::vector<unsigned int> block_component(dim + 1, 0);
      block_component[dim] = 1;
      DoFRenumbering::component_wise(dof_handler, block_component);
      const std::vector<types::global_dof_index> dofs_per_block =
        DoFTools::count_dofs_per_fe_block(dof_handler, block_component);
      const types::global_dof_index n_u = dofs_per_block[0],
                                    n_p = dofs_per_block[1];

      const IndexSet &owned    = dof_handler.locally_owned_dofs();
      const IndexSet  relevant =
        DoFTools::extract_locally_relevant_dofs(dof_handler);
      owned_partitioning    = {owned.get_view(0, n_u),
                               owned.get_view(n_u, n_u + n_p)};
      relevant_partitioning = {relevant.get_view(0, n_u),
                               relevant.get_view(n_u, n_u + n_p)};

      // Moving solids: a sparsity that does not depend on where they are.
      make_constraints(!moving_solids);

      velocity_components_coupled =
        velocity_components_coupled ||
        couples_velocity_components(Assembly::steady_stokes);
      // The matrix-free path assembles no global matrix; a matrix-based
      // solve (transient, convective) allocates it on first assembly, as
      // do moving grains, whose pattern depends on where they are.
      pattern_constraints.clear();
      if (use_matrix_free(Assembly::steady_stokes) || moving_solids ||
          use_transient_matrix_free())
        {
          preconditioner.reset();
          system_matrix.clear();
        }
      else
        reinit_system_matrix();
      pressure_mass_matrix.clear();
      pressure_laplace_matrix.clear();
      if (solver_parameters.schur !=
          SolverParameters::Schur::least_squares_commutator)
      {
        Table<2, DoFTools::Coupling> coupling(dim + 1, dim + 1);
        for (unsigned int c = 0; c < dim + 1; ++c)
          for (unsigned int d = 0; d < dim + 1; ++d)
            coupling[c][d] = (c == dim && d == dim) ? DoFTools::always :
                                                      DoFTools::none;
        const BlockDynamicSparsityPattern dsp =
          make_block_pattern(dof_handler,
                             coupling,
                             constraints,
                             relevant_partitioning,
                             moving_solids);
        pressure_mass_matrix.reinit(owned_partitioning, dsp, mpi_communicator);
        if (solver_parameters.schur ==
            SolverParameters::Schur::cahouet_chabard)
          pressure_laplace_matrix.reinit(owned_partitioning,
                                         dsp,
                                         mpi_communicator);
      }

      solution.reinit(owned_partitioning,
                      relevant_partitioning,
                      mpi_communicator);
      old_solution.reinit(solution);
      older_solution.reinit(solution);
      system_rhs.reinit(owned_partitioning, mpi_communicator);
      steps_since_start = 0;
      transient_matrix_free.reset();
      if (solver_parameters.linear_solver ==
            SolverParameters::LinearSolver::matrix_free ||
          use_transient_matrix_free())
        setup_matrix_free_dofs();
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::couples_velocity_components(
      const Assembly kind) const
    {
      return solver_parameters.grad_div > 0 ||
             solver_parameters.grad_div_cell_factor > 0 ||
             kind == Assembly::steady_newton;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::reinit_system_matrix()
    {
      // The preconditioner refers to the old matrix.
      preconditioner.reset();
      system_matrix.clear();
      Table<2, DoFTools::Coupling> coupling(dim + 1, dim + 1);
      for (unsigned int c = 0; c < dim + 1; ++c)
        for (unsigned int d = 0; d < dim + 1; ++d)
          {
            const bool velocity_pair = (c < dim && d < dim);
            if (c == dim && d == dim)
              coupling[c][d] =
                smooth_solid_pressure() ? DoFTools::always : DoFTools::none;
            else if (velocity_pair && c != d && !velocity_components_coupled)
              coupling[c][d] = DoFTools::none;
            else
              coupling[c][d] = DoFTools::always;
          }
      system_matrix.reinit(owned_partitioning,
                           make_block_pattern(dof_handler,
                                              coupling,
                                              constraints,
                                              relevant_partitioning,
                                              moving_solids),
                           mpi_communicator);
    }


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
                // diverged without it (doc/solver_study.md, "Oseen").
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


    template <int dim>
    IndexSet
    PenalizedNavierStokes<dim>::owned_constrained_dofs() const
    {
      IndexSet constrained(dof_handler.n_dofs());
      for (const auto i : dof_handler.locally_owned_dofs())
        if (constraints.is_constrained(i))
          constrained.add_index(i);
      constrained.compress();
      return constrained;
    }


    template <int dim>
    IndexSet
    PenalizedNavierStokes<dim>::constrained_velocity_dofs() const
    {
      // The velocity block comes first in the DoF numbering.
      return owned_constrained_dofs().get_view(0, owned_partitioning[0].size());
    }


    namespace
    {
      /// The ML smoother of the velocity block. Chebyshev's polynomial
      /// needs a real spectrum; a convective block's is not.
      const char *
      velocity_smoother_name(const SolverParameters::AmgSmoother smoother,
                             const bool                          convection)
      {
        using S = SolverParameters::AmgSmoother;
        switch (smoother)
          {
            case S::chebyshev:
              return "Chebyshev";
            case S::symmetric_gauss_seidel:
              return "symmetric Gauss-Seidel";
            case S::ilu:
              return "ILU";
            default:
              return convection ? "ILU" : "Chebyshev";
          }
      }
    } // namespace


    template <int dim>
    void
    PenalizedNavierStokes<dim>::build_preconditioner(
      const bool      convection,
      const IndexSet &constrained)
    {
      TimerOutput::Scope t(timer, "fluid: preconditioner setup");
      preconditioner.reset();
      // How much of the system the grains fix (their rows keep only a
      // diagonal in the pattern).
      pcout << "      preconditioner built: "
            << Utilities::MPI::sum(constrained.n_elements(), mpi_communicator)
            << " of "
            << owned_partitioning[0].size()
            << " velocity DoFs constrained (grains, walls, hanging)"
            << std::endl;
      std::vector<std::vector<bool>> constant_modes;
      const FEValuesExtractors::Vector velocities(0);
      DoFTools::extract_constant_modes(dof_handler,
                                       fe.component_mask(velocities),
                                       constant_modes);
      preconditioner = std::make_unique<BlockSchurPreconditioner>(
        system_matrix,
        pressure_mass_matrix,
        solver_parameters.schur ==
            SolverParameters::Schur::cahouet_chabard ?
          &pressure_laplace_matrix :
          nullptr,
        constant_modes,
        velocity_amg_sweeps_in_use(),
        velocity_smoother_name(solver_parameters.velocity_amg_smoother,
                               convection),
        solver_parameters.schur,
        solver_parameters.schur_inner_tolerance,
        solver_parameters.direct_velocity_solve,
        schur_inner_solver(),
        solver_parameters.velocity_amg_smoothed_aggregation);
      preconditioner_convection  = convection;
      preconditioner_iterations  = 0;
      preconditioner_constraints = constrained;
    }


    template <int dim>
    unsigned int
    PenalizedNavierStokes<dim>::solve_linear(const bool convection)
    {
      TimerOutput::Scope t(timer, "fluid: solve");

      // A kept preconditioner (same mesh, sparsity and constrained DoFs,
      // same kind of block) preconditions the new matrix: FGMRES stays
      // exact, and the iteration count tells when to rebuild. Rigid nodes
      // that grains entered or left spoil it: on the small Hele-Shaw scene
      // at 16 kPa, 400-600 changed DoFs (0.4 %) failed it every step.
      const IndexSet constrained = constrained_velocity_dofs();
      const bool     kept =
        preconditioner != nullptr && solver_parameters.reuse_preconditioner &&
        preconditioner_convection == convection &&
        Utilities::MPI::min(constrained == preconditioner_constraints ? 1 : 0,
                            mpi_communicator) == 1;
      if (!kept)
        build_preconditioner(convection, constrained);

      BlockVector x(owned_partitioning, mpi_communicator);
      x = solution; // start from the previous state: cheap re-solves
      constraints.set_zero(x);

      if (!boundary_conditions.has_pressure_face())
        {
          // Only velocity conditions: the pressure constant is a null vector
          // of the (transposed) system, and interpolated boundary data make
          // the continuity rows slightly inconsistent (net flux != 0 at the
          // discrete level). Project the right-hand side onto the range.
          double       sum   = 0;
          unsigned int count = 0;
          for (const auto i : owned_partitioning[1])
            {
              const auto global = i + owned_partitioning[0].size();
              if (!constraints.is_constrained(global))
                {
                  sum += system_rhs(global);
                  ++count;
                }
            }
          sum   = Utilities::MPI::sum(sum, mpi_communicator);
          count = Utilities::MPI::sum(count, mpi_communicator);
          for (const auto i : owned_partitioning[1])
            {
              const auto global = i + owned_partitioning[0].size();
              if (!constraints.is_constrained(global))
                system_rhs(global) -= sum / count;
            }
          system_rhs.compress(VectorOperation::insert);
        }

      const double rhs_norm = system_rhs.l2_norm();
      SolverControl control(solver_parameters.max_linear_iterations,
                            std::max(solver_parameters.linear_tolerance *
                                       rhs_norm,
                                     1e-300),
                            false,
                            false);
      // A well-posed singular system (no pressure face) is consistent:
      // FGMRES converges in the complement of the constant pressure.
      SolverFGMRES<BlockVector> solver(
        control, SolverFGMRES<BlockVector>::AdditionalData(
          solver_parameters.krylov_restart));
      // A kept preconditioner may take 'rebuild factor' times the
      // iterations of its first solve (+ 5); where that does not suffice,
      // a new one solves again from the same start with the whole budget.
      // Where a new one fails too, the velocity V-cycle is too weak for this
      // matrix (late steps of a transient pack, whose grains moved: the
      // small Hele-Shaw cell at 8.1 ms stalled at 2.7e-4 with 4 sweeps and
      // converged in 493 iterations with 8): double its sweeps, twice at most.
      if (kept)
        control.set_max_steps(std::min<unsigned int>(
          solver_parameters.max_linear_iterations,
          solver_parameters.preconditioner_rebuild_factor *
              preconditioner_iterations +
            5));
      const BlockVector  start = x;
      const unsigned int max_sweeps = 4 * solver_parameters.velocity_amg_sweeps;
      for (bool fresh = !kept;;)
        try
          {
            if (rhs_norm > 0)
              solver.solve(system_matrix, x, system_rhs, *preconditioner);
            break;
          }
        catch (const SolverControl::NoConvergence &e)
          {
            const unsigned int sweeps = velocity_amg_sweeps_in_use();
            AssertThrow(!fresh || 2 * sweeps <= max_sweeps,
                        ExcMessage(
                          linear_solver_failure(e, control.tolerance()) +
                          locate_largest_residual(x)));
            if (fresh)
              {
                velocity_amg_sweeps = 2 * sweeps;
                base::warn("the fluid solver did not converge in " +
                             std::to_string(e.last_step) +
                             " iterations; retried, and goes on, with " +
                             std::to_string(velocity_amg_sweeps) +
                             " velocity AMG sweeps instead of " +
                             std::to_string(sweeps) +
                             " ('fluid solver/velocity amg sweeps'): "
                             "slower steps",
                           mpi_communicator);
              }
            else
              pcout << "      kept preconditioner: no convergence in "
                    << e.last_step << " iterations, rebuilt" << std::endl;
            build_preconditioner(convection, constrained);
            control.set_max_steps(solver_parameters.max_linear_iterations);
            x     = start;
            fresh = true;
          }
      const unsigned int iterations = rhs_norm > 0 ? control.last_step() : 0;
      // The first solve with a preconditioner sets its reference count.
      if (preconditioner_iterations == 0)
        preconditioner_iterations = std::max(iterations, 1u);
      // A zero right-hand side (fluid and grains at rest) needs no solve.
      return accept_linear_solution(x, iterations);
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::viscous_beta_floor() const
    {
      double domain_size = 0;
      const auto box = GridTools::compute_bounding_box(triangulation);
      for (unsigned int d = 0; d < dim; ++d)
        domain_size = std::max(domain_size, box.side_length(d));
      return fluid_parameters.viscosity / (domain_size * domain_size);
    }


    template <int dim>
    std::string
    PenalizedNavierStokes<dim>::linear_solver_failure(
      const SolverControl::NoConvergence &e,
      const double                        tolerance)
    {
      return "The fluid solver (FGMRES) did not converge in " +
             std::to_string(e.last_step) + " iterations (residual " +
             Utilities::to_string(e.last_residual) + " vs " +
             Utilities::to_string(tolerance) +
             "). Raise 'fluid solver/max linear iterations' or check the "
             "scene (time step, theta, mesh).";
    }


    template <int dim>
    std::string
    PenalizedNavierStokes<dim>::locate_largest_residual(
      const BlockVector &x) const
    {
      BlockVector residual(owned_partitioning, mpi_communicator);
      system_matrix.vmult(residual, x);
      residual.sadd(-1., 1., system_rhs);

      // Per block: the largest |r_i| over the owned rows, then its support
      // point and whether the row is imposed (rigid or boundary).
      std::array<double, 2>                  largest = {{-1., -1.}};
      std::array<types::global_dof_index, 2> row     = {{0, 0}};
      for (unsigned int b = 0; b < 2; ++b)
        for (const auto i : owned_partitioning[b])
          {
            // Block-local index i; the combined handler numbers the
            // pressure after all velocities.
            const double r = std::abs(residual.block(b)(i));
            if (r > largest[b])
              {
                largest[b] = r;
                row[b]     = b == 0 ? i : i + owned_partitioning[0].size();
              }
          }

      const Quadrature<dim> support(fe.get_unit_support_points());
      FEValues<dim> fe_values(fe, support, update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
      std::array<Point<dim>, 2> where;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dof_indices);
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              for (unsigned int b = 0; b < 2; ++b)
                if (largest[b] >= 0 && dof_indices[k] == row[b])
                  {
                    fe_values.reinit(cell);
                    where[b] = fe_values.quadrature_point(k);
                  }
          }

      std::string text;
      const char *rows[2] = {"momentum", "continuity"};
      for (unsigned int b = 0; b < 2; ++b)
        {
          // The rank holding the largest value reports it.
          const double global =
            Utilities::MPI::max(largest[b], mpi_communicator);
          Point<dim> point;
          int        imposed = 0;
          if (largest[b] == global)
            {
              point   = where[b];
              imposed = constraints.is_constrained(row[b]) ? 1 : 0;
            }
          // Only one rank contributes a nonzero point (ties: the sum of
          // identical values is rare and only blurs the location).
          const unsigned int owner_count = Utilities::MPI::sum(
            largest[b] == global ? 1u : 0u, mpi_communicator);
          for (unsigned int d = 0; d < dim; ++d)
            point[d] = Utilities::MPI::sum(point[d], mpi_communicator) /
                       owner_count;
          imposed = Utilities::MPI::max(imposed, mpi_communicator);
          std::ostringstream out;
          out << (b == 0 ? " Largest residual: " : "; ") << rows[b]
              << " rows " << global << " at (" << point << ") m"
              << (imposed ? " (an imposed row)" : "");
          text += out.str();
        }
      return text + ".";
    }


    template <int dim>
    unsigned int
    PenalizedNavierStokes<dim>::accept_linear_solution(
      BlockVector       &x,
      const unsigned int iterations)
    {
      constraints.distribute(x);
      if (!boundary_conditions.has_pressure_face())
        {
          // Pressure is defined up to a constant: report zero mean.
          solution          = x;
          const double mean = VectorTools::compute_mean_value(
            dof_handler, QGauss<dim>(fe.degree + 1), solution, dim);
          x.block(1).add(-mean);
        }
      solution = x;

      AssertThrow(std::isfinite(x.l2_norm()),
                  ExcMessage("The fluid solution is not finite (NaN or Inf)."));
      statistics.linear_iterations = iterations;
      statistics.total_linear_iterations += iterations;
      return iterations;
    }


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
            Tensor<1, dim> f;
            f[fe.system_to_component_index(k).first] = weight * r;
            rigid_reactions.emplace_back(grain,
                                         fe_values.quadrature_point(k),
                                         f);
          };
          // A node whose target blends grains (penalization limit) hands
          // each its share of the reaction.
          const auto add_node = [&](const unsigned int            k,
                                    const types::global_dof_index i,
                                    const double                  weight) {
            const auto shares = rigid_dof_shares.find(i);
            if (shares == rigid_dof_shares.end())
              add(k, rigid_dof_grain.at(i), weight);
            else
              for (const auto &[grain, share] : shares->second)
                add(k, grain, weight * share);
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
    PenalizedNavierStokes<dim>::solve_steady_stokes(const double dt)
    {
      statistics       = SolveStatistics();
      last_time_step   = dt;
      last_was_steady  = true;
      make_constraints();
      if (use_matrix_free(Assembly::steady_stokes))
        solve_matrix_free(Assembly::steady_stokes, dt);
      else
        {
          assemble(Assembly::steady_stokes, dt, 1);
          solve_linear(false);
        }
      statistics.nonlinear_iterations = 1;
      compute_reactions(Assembly::steady_stokes, dt, 1);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::solve_steady_navier_stokes(const double dt)
    {
      statistics      = SolveStatistics();
      last_time_step  = dt;
      last_was_steady = true;
      make_constraints();
      // A Stokes solve gives the first iterate.
      if (use_matrix_free(Assembly::steady_stokes))
        solve_matrix_free(Assembly::steady_stokes, dt);
      else
        {
          assemble(Assembly::steady_stokes, dt, 1);
          solve_linear(false);
        }
      const Assembly kind =
        solver_parameters.nonlinear_method == SolverParameters::Nonlinear::newton ?
          Assembly::steady_newton :
          Assembly::steady_picard;
      pseudo_time_cfl = solver_parameters.pseudo_time_cfl;
      double last_change = std::numeric_limits<double>::max();
      for (unsigned int k = 1; k <= solver_parameters.max_nonlinear_iterations;
           ++k)
        {
          BlockVector previous(owned_partitioning, mpi_communicator);
          previous = solution;
          assemble(kind, dt, 1);
          solve_linear(true);
          BlockVector change(owned_partitioning, mpi_communicator);
          change = solution;
          change.block(0) -= previous.block(0);
          previous = solution;
          const double norm = previous.block(0).l2_norm();
          statistics.nonlinear_change =
            change.block(0).l2_norm() / std::max(norm, 1e-300);
          statistics.nonlinear_iterations = k;
          pcout << "      nonlinear iteration " << k << ": change "
                << statistics.nonlinear_change << ", "
                << statistics.linear_iterations << " FGMRES iterations";
          if (pseudo_time_cfl > 0)
            pcout << ", cfl " << pseudo_time_cfl;
          pcout << std::endl;
          if (pseudo_time_cfl > 0 && statistics.nonlinear_change < last_change)
            pseudo_time_cfl *= solver_parameters.pseudo_time_growth;
          last_change = statistics.nonlinear_change;
          if (statistics.nonlinear_change < solver_parameters.nonlinear_tolerance)
            {
              pseudo_time_cfl = 0;
              // The Picard operator at the converged state: A(u) u - f.
              compute_reactions(Assembly::steady_picard, dt, 1);
              return;
            }
        }
      AssertThrow(false,
                  ExcMessage(
                    "Steady Navier-Stokes did not converge in " +
                    std::to_string(solver_parameters.max_nonlinear_iterations) +
                    " iterations (last relative change " +
                    Utilities::to_string(statistics.nonlinear_change) +
                    "). Raise 'fluid solver/max nonlinear iterations', use "
                    "newton, or march in time (mode = transient)."));
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::start_time_stepping()
    {
      old_solution      = solution;
      older_solution    = solution;
      steps_since_start = 0;
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::max_velocity_per_cell_size() const
    {
      const QGauss<dim> quadrature(2);
      FEValues<dim>     fe_values(fe, quadrature, update_values);
      const FEValuesExtractors::Vector velocities(0);
      std::vector<Tensor<1, dim>>      u(quadrature.size());
      double                           rate = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values[velocities].get_function_values(solution, u); // ghosted
            double speed = 0;
            for (const auto &v : u)
              speed = std::max(speed, v.norm());
            rate = std::max(rate, speed / cell->minimum_vertex_distance());
          }
      return Utilities::MPI::max(rate, mpi_communicator);
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::advance(const double       dt,
                                        const unsigned int bdf_order)
    {
      statistics      = SolveStatistics();
      // The history moves at the start of a step, so that after it u^n and
      // u^{n-1} are still there for the reaction force (a moving grain's
      // force needs u~ of this step).
      if (steps_since_start > 0)
        {
          older_solution = old_solution;
          old_solution   = solution;
        }
      // BDF2 on steps of changing length (BDFCoefficients); a step more
      // than max_bdf2_step_ratio times the last starts again with BDF1.
      // After a checkpoint without the last step's length it is taken equal.
      const double ratio =
        previous_transient_step > 0 ? dt / previous_transient_step : 1.;
      const unsigned int order =
        (steps_since_start == 0 || ratio > max_bdf2_step_ratio) ? 1 : bdf_order;
      bdf_step_ratio          = (order == 1) ? 1. : ratio;
      previous_transient_step = dt;
      last_time_step  = dt;
      last_bdf_order  = order;
      last_was_steady = false;
      make_constraints();
      if (use_transient_matrix_free())
        advance_matrix_free(dt, order);
      else
        {
          assemble(Assembly::transient, dt, order);
          solve_linear(true);
          compute_reactions(Assembly::transient, dt, order);
        }
      statistics.nonlinear_iterations = 1;

      BlockVector change(owned_partitioning, mpi_communicator), u(change);
      change = solution;
      u      = old_solution;
      change.block(0) -= u.block(0);
      u = solution;
      last_change =
        change.block(0).l2_norm() / std::max(u.block(0).l2_norm(), 1e-300);
      ++steps_since_start;
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::relative_velocity_change() const
    {
      return last_change;
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

    template class PenalizedNavierStokes<2>;
    template class PenalizedNavierStokes<3>;
  } // namespace fluid
} // namespace softsand
