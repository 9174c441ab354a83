// PenalizedNavierStokes: the matrix-based linear solve. FGMRES with the
// block Schur preconditioner, its set-up and reuse, and the messages a
// failed solve leaves.

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


    // Instantiated member by member: the class's other members are
    // defined in penalized_navier_stokes.cc and its sibling files.
    template void
    PenalizedNavierStokes<2>::build_preconditioner(const bool      convection,
                                                   const IndexSet &constrained);
    template unsigned int
    PenalizedNavierStokes<2>::solve_linear(const bool convection);
    template double
    PenalizedNavierStokes<2>::viscous_beta_floor() const;
    template std::string
    PenalizedNavierStokes<2>::linear_solver_failure(
      const SolverControl::NoConvergence &e,
      const double                        tolerance);
    template std::string
    PenalizedNavierStokes<2>::locate_largest_residual(
      const BlockVector &x) const;
    template unsigned int
    PenalizedNavierStokes<2>::accept_linear_solution(
      BlockVector       &x,
      const unsigned int iterations);
    template void
    PenalizedNavierStokes<3>::build_preconditioner(const bool      convection,
                                                   const IndexSet &constrained);
    template unsigned int
    PenalizedNavierStokes<3>::solve_linear(const bool convection);
    template double
    PenalizedNavierStokes<3>::viscous_beta_floor() const;
    template std::string
    PenalizedNavierStokes<3>::linear_solver_failure(
      const SolverControl::NoConvergence &e,
      const double                        tolerance);
    template std::string
    PenalizedNavierStokes<3>::locate_largest_residual(
      const BlockVector &x) const;
    template unsigned int
    PenalizedNavierStokes<3>::accept_linear_solution(
      BlockVector       &x,
      const unsigned int iterations);
  } // namespace fluid
} // namespace softsand
