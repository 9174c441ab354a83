// PenalizedNavierStokes: its DoFs and matrices, the transfer of its fields
// across mesh changes and checkpoints, and the time stepping (the steady
// solves and advance()). The momentum terms, the grains' constraints, the
// linear solve and the forces on grains are in the files beside it
// (momentum_assembly.cc, solid_constraints.cc,
// navier_stokes_linear_solve.cc, grain_reactions.cc).

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
      // The steady matrix-free operators know rigid nodes and the penalty,
      // not the blended constraints of the penalization limit (the
      // transient one takes them as it takes rigid nodes).
      if (fluid_parameters.solid_model ==
            FluidParameters::SolidModel::penalization_limit &&
          solver_parameters.linear_solver ==
            SolverParameters::LinearSolver::matrix_free)
        base::throw_invalid_parameter(
          "fluid solver/linear solver",
          "matrix free",
          "fluid/solid model = penalization limit needs 'matrix based'");
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
      // The last step's relative change, as advance() left it (the coupled
      // step's accuracy limit reads it): u^n and u^{n-1} are both restored.
      if (steps_done > 0)
        {
          const double norm = values[0].block(0).l2_norm();
          values[0].block(0) -= values[1].block(0);
          last_change = values[0].block(0).l2_norm() / std::max(norm, 1e-300);
        }
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
          // The porous cells' pore inertia (rho / phi) is on the
          // matrix-free step only.
          AssertThrow(solid_field == nullptr || !solid_field->has_porous_zone(),
                      ExcMessage(
                        "Parameter coupling/hybrid model/resolved radius is "
                        "set, but the transient step is matrix based (fluid "
                        "solver/transient solver, or a solid model other than "
                        "rigid nodes or the penalization limit): the hybrid "
                        "model's porous cells are implemented on the "
                        "matrix-free transient step and the steady solves. "
                        "Set fluid solver/transient solver = matrix free, or "
                        "resolved radius = none."));
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


    template class PenalizedNavierStokes<2>;
    template class PenalizedNavierStokes<3>;
  } // namespace fluid
} // namespace softsand
