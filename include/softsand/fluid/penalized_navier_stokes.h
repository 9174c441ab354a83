#ifndef softsand_fluid_penalized_navier_stokes_h
#define softsand_fluid_penalized_navier_stokes_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <softsand/fluid/bdf_coefficients.h>
#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/boundary_conditions.h>
#include <softsand/fluid/fluid_parameters.h>
#include <softsand/fluid/solid_field.h>

#include <deal.II/lac/full_matrix.h>

#include <functional>
#include <map>
#include <unordered_map>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <cstdint>
#include <memory>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * Incompressible Navier-Stokes with the paper's penalization (Eq. 6) on a
     * distributed octree mesh, Taylor-Hood Q2-Q1 elements
     * (doc/architecture.md, "Where each equation lives"). Where solids cover
     * the fluid (void fraction vf < 1) the density is
     * rho* = rho (1 + Theta (1 - vf)) and the momentum predictor relaxes to
     * the solid's rigid velocity u_s:
     *
     *   rho* (u^{n+1} - u~) / dt + rho (w . grad) u^{n+1} - mu lap u^{n+1}
     *     + grad p^{n+1} = f,   div u^{n+1} = 0,  u~ = vf u^n + (1 - vf) u_s
     *
     * (BDF1 shown; BDF2 on steps of changing length is analogous,
     * BDFCoefficients). The steady modes solve the fixed point
     * of the same scheme, u^{n+1} = u^n: a Brinkman term
     * beta (u - u_s) with beta = rho (1 + Theta (1 - vf)) (1 - vf) / dt, so
     * the steady solution equals the time-marched steady state exactly.
     */
    template <int dim>
    class PenalizedNavierStokes
    {
    public:
      using BlockVector = TrilinosWrappers::MPI::BlockVector;

      /// What one call of the linear solver did.
      struct SolveStatistics
      {
        unsigned int linear_iterations    = 0; // of the last linear solve
        unsigned int total_linear_iterations = 0;
        unsigned int nonlinear_iterations = 0;
        double       nonlinear_change     = 0;
      };

      PenalizedNavierStokes(parallel::distributed::Triangulation<dim> &tria,
                            const FluidParameters          &fluid_parameters,
                            const SolverParameters         &solver_parameters,
                            const BoundaryConditions<dim>  &boundary_conditions,
                            ConditionalOStream             &pcout,
                            TimerOutput                    &timer);

      /// Distribute dofs, build constraints and sparsity after any change of
      /// the mesh. Fields are reset to zero.
      void
      setup_dofs();

      /// The solids seen by the fluid (nullptr: pure fluid).
      void
      set_solid_field(const SolidField<dim> *solids);

      /**
       * Solids that move between solves (the coupled loop): the nodes they
       * constrain change from solve to solve, so the matrix sparsity is
       * built without them (hanging nodes and boundary conditions only)
       * and stays valid; call before setup_dofs().
       */
      void
      set_moving_solids(const bool moving);

      /// Before the mesh changes: pack the current and the two previous
      /// solutions for transfer to the new mesh.
      void
      prepare_for_coarsening_and_refinement();

      /// After the mesh changed: new dofs and sparsity, and the packed
      /// solutions interpolated onto them; BDF history is kept.
      void
      transfer_after_coarsening_and_refinement();

      /// Attach the current and previous solutions to the triangulation
      /// for Triangulation::save() (checkpoint).
      void
      prepare_for_serialization();

      /// After Triangulation::load(): dofs and the solutions read back,
      /// with the BDF step count @p steps_done of the checkpoint and the
      /// length of its last step (0: unknown, taken equal to the next).
      void
      deserialize(const unsigned int steps_done,
                  const double       previous_step = 0);

      /// The length of the last advance() step (0 before the first).
      double
      last_transient_step() const
      {
        return previous_transient_step;
      }

      /// The last advance() step over the one before it (1 after a BDF1
      /// step or a checkpoint).
      double
      last_step_ratio() const
      {
        return bdf_step_ratio;
      }

      /// The largest |u| / h over the cells (h: a cell's shortest vertex
      /// distance, u at its Gauss points): times a step, the Courant number.
      double
      max_velocity_per_cell_size() const;

      /// Time steps since start_time_stepping() (BDF1 on the first).
      unsigned int
      n_steps_done() const
      {
        return steps_since_start;
      }

      /// Time of the boundary conditions and the body force.
      void
      set_time(const double time);

      /// One Stokes-Brinkman solve (no convection); @p penalty_time_step is
      /// the dt in the Brinkman coefficient.
      void
      solve_steady_stokes(const double penalty_time_step);

      /// Newton or Picard iterations to the steady Navier-Stokes-Brinkman
      /// solution, starting from the current solution.
      void
      solve_steady_navier_stokes(const double penalty_time_step);

      /// Prepare time marching from the current solution (the initial state).
      void
      start_time_stepping();

      /// One BDF step to the current time (set_time() first). The first step
      /// after start_time_stepping() is BDF1.
      void
      advance(const double time_step, const unsigned int bdf_order);

      /**
       * Force of the fluid on the box faces after a solve (summed over
       * ranks): the discrete reaction of the velocity-constrained faces
       * plus the prescribed pressure on pressure faces. With the grains'
       * reaction forces and the body force it closes the momentum balance
       * to the solver tolerance.
       */
      Tensor<1, dim>
      boundary_force() const
      {
        return last_boundary_force;
      }

      /// ||u^{n+1} - u^n|| / ||u^{n+1}|| of the last step.
      double
      relative_velocity_change() const;

      /**
       * Loop over the quadrature points covered by solids and hand to @p f
       * the solid index, the point and the reaction force the fluid exerts
       * on the solid there, times JxW: the penalization term of the momentum
       * equation, (1 - vf) rho* (u^{n+1} - u_s)/dt (steady: beta (u - u_s)).
       * Summed over a solid it is the exact discrete fluid force on it.
       */
      void
      for_each_solid_reaction(
        const std::function<void(const int,
                                 const Point<dim> &,
                                 const Tensor<1, dim> &)> &f) const;

      /**
       * The paper's Eq. (7) for diagnostics: hand to @p f the solid index,
       * the point and (mu lap u - grad p) (1 - vf) JxW at points covered by
       * solids. It misses the stress jumps across element faces.
       */
      void
      for_each_solid_stress_divergence(
        const std::function<void(const int,
                                 const Point<dim> &,
                                 const Tensor<1, dim> &)> &f) const;

      const DoFHandler<dim> &
      get_dof_handler() const
      {
        return dof_handler;
      }
      const FESystem<dim> &
      get_fe() const
      {
        return fe;
      }
      /// Ghosted solution (velocity block 0, pressure block 1).
      const BlockVector &
      get_solution() const
      {
        return solution;
      }
      BlockVector &
      get_solution()
      {
        return solution;
      }
      const SolveStatistics &
      get_statistics() const
      {
        return statistics;
      }
      /// The part of the grains' volume (as the mesh sees it) that the
      /// freed contact cells give to the fluid (FluidParameters::
      /// free_contact_cells); 0 when no cell is freed.
      double
      freed_solid_fraction() const;
      types::global_dof_index
      n_dofs() const
      {
        return dof_handler.n_dofs();
      }

    private:
      enum class Assembly
      {
        steady_stokes,
        steady_picard,
        steady_newton,
        transient
      };

      /// Hanging nodes, boundary conditions and (with @p with_solids) the
      /// nodes that solids constrain.
      void
      make_constraints(const bool with_solids = true);
      /**
       * Whether an assembly of @p kind writes entries between different
       * velocity components: grad-div and the Newton derivative of the
       * convection do; Stokes, Picard and the time step's Oseen operator
       * act on each component alone. Without those entries the 3D
       * Taylor-Hood velocity rows hold about 2.6x fewer nonzeros.
       */
      bool
      couples_velocity_components(const Assembly kind) const;
      /// Sparsity of system_matrix from the current constraints, with the
      /// velocity components coupled iff velocity_components_coupled.
      void
      reinit_system_matrix();
      /// Fully distributed copies of the three solutions in the ghosted
      /// vectors, with hanging-node values restored.
      void
      set_solutions(const std::vector<BlockVector *> &values);
      /**
       * Constrain the velocity nodes of @p dof that move with a grain (rigid
       * nodes: within radius + @p inflation; constrained interiors: the
       * nodes of cells wholly inside one grain), unless already constrained.
       * With @p grain_of_dof the constraint carries the grain's rigid
       * velocity and the grain is recorded; without, it is homogeneous (the
       * multigrid levels).
       */
      void
      add_solid_constraints(
        const DoFHandler<dim>                  &dof,
        AffineConstraints<double>              &constraints,
        const double                            inflation,
        std::unordered_map<types::global_dof_index, int> *grain_of_dof) const;
      /// Penalization limit: constrain the velocity nodes that solids
      /// cover to their blended penalized update (penalization_limit.h)
      /// and record the grains of each in #rigid_dof_grain and
      /// #rigid_dof_shares.
      void
      add_penalization_limit_constraints();
      /// Distance by which the rigid-node model grows the grains (m).
      double
      rigid_node_inflation() const;
      /// The matrix-free path: velocity and pressure DoFHandlers numbered
      /// like the blocks of the combined one.
      void
      setup_matrix_free_dofs();
      /// Matrix-free assembly of the right-hand side and the Schur blocks,
      /// then FGMRES with the multigrid block preconditioner.
      unsigned int
      solve_matrix_free(const Assembly kind, const double time_step);
      bool
      use_matrix_free(const Assembly kind) const
      {
        // The matrix-free operator has no grad-div term; of its Schur
        // blocks only the commutator knows the pressure regions.
        return solver_parameters.linear_solver ==
                 SolverParameters::LinearSolver::matrix_free &&
               kind == Assembly::steady_stokes &&
               solver_parameters.schur !=
                 SolverParameters::Schur::discrete_brinkman &&
               solver_parameters.grad_div == 0 &&
               solver_parameters.grad_div_cell_factor == 0 &&
               (!boundary_conditions.has_pressure_regions() ||
                solver_parameters.schur ==
                  SolverParameters::Schur::least_squares_commutator);
      }
      /// Whether advance() takes the transient matrix-free path.
      bool
      use_transient_matrix_free() const
      {
        // Grad-div is refused with it (SolverParameters). Not
        // rigid_nodes(): the choice is made before grains attach. Automatic
        // only in 3D, where it was measured faster; on the 2D transient
        // convergence study its FGMRES stalls at 1.7e-7 relative residual.
        if (solver_parameters.transient_solver_automatic)
          return dim == 3 &&
                 (fluid_parameters.solid_model ==
                    FluidParameters::SolidModel::rigid_nodes ||
                  fluid_parameters.solid_model ==
                    FluidParameters::SolidModel::penalization_limit) &&
                 solver_parameters.grad_div == 0 &&
                 solver_parameters.grad_div_cell_factor == 0;
        return solver_parameters.transient_solver ==
               SolverParameters::LinearSolver::matrix_free;
      }
      /// The transient matrix-free path, per mesh: MatrixFree on the mesh's
      /// own constraints (hanging nodes, walls, pressure regions), the
      /// pattern of the assembled pieces, the per-mesh right-hand side.
      void
      setup_transient_matrix_free();
      /// One BDF step of @p order on the transient matrix-free path, then
      /// its reactions (rigid nodes, walls) from the rows' residual.
      unsigned int
      advance_matrix_free(const double time_step, const unsigned int order);
      /// The phases of advance_matrix_free(). This step's constraints,
      /// coefficients, right-hand side and lifting, the traction and
      /// smoothing terms (transient_matrix_free.cc).
      void
      assemble_matrix_free_step(const double time_step, const unsigned int order);
      /// D = diag(A), X = B D^-1 B^T + C and X's AMG
      /// (transient_matrix_free_solve.cc).
      void
      setup_matrix_free_preconditioner(const double       time_step,
                                       const unsigned int order);
      /// FGMRES with the block preconditioner; the solution accepted.
      void
      solve_matrix_free_step();
      /// The reactions of rigid nodes and walls from their rows' residual
      /// (transient_matrix_free_reactions.cc).
      void
      compute_matrix_free_reactions(const unsigned int order);
      /// The force of the prescribed pressures p_b on the pressure faces of
      /// this rank's cells (both paths' boundary force).
      Tensor<1, dim>
      pressure_face_force() const;
      /// Cell matrix, right-hand side and dof indices before constraints.
      using CellCallback =
        std::function<void(const typename DoFHandler<dim>::active_cell_iterator &,
                           const FullMatrix<double> &,
                           const Vector<double> &,
                           const std::vector<types::global_dof_index> &)>;

      /// Which cells a callback assembly visits, and in @p rows (one per
      /// cell DoF, all true on entry) which rows of the cell's system the
      /// callback reads: the others are left zero, not computed.
      using CellFilter = std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &,
        std::vector<bool> &rows)>;

      /// Assemble the system; with @p cell_callback, hand the local system
      /// of each cell that @p cell_filter accepts to it instead (for
      /// discrete reactions).
      void
      assemble(const Assembly      kind,
               const double        time_step,
               const unsigned int  bdf_order,
               const CellCallback *cell_callback = nullptr,
               const CellFilter   *cell_filter   = nullptr);
      /// After a solve, in one assembly pass: the rigid-node model's force
      /// of the fluid on each constrained node, F - A u of its row (the
      /// exact discrete reaction), and the force of the fluid on the
      /// velocity-constrained boundary faces, the same residual of their
      /// rows (hanging boundary nodes included: their parents lie on the
      /// same faces) plus p_b on the pressure faces.
      void
      compute_reactions(const Assembly     kind,
                        const double       time_step,
                        const unsigned int bdf_order);
      /// Penalization with the nodes of cells wholly inside a grain
      /// constrained to its rigid velocity.
      bool
      constrained_interiors() const
      {
        return solid_field != nullptr &&
               fluid_parameters.solid_model ==
                 FluidParameters::SolidModel::penalization &&
               fluid_parameters.constrain_grain_interiors;
      }
      bool
      rigid_nodes() const
      {
        return solid_field != nullptr &&
               fluid_parameters.solid_model ==
                 FluidParameters::SolidModel::rigid_nodes;
      }
      /// The Theta -> infinity limit of the penalized update, node by node
      /// (penalization_limit.h).
      bool
      penalization_limit() const
      {
        return solid_field != nullptr &&
               fluid_parameters.solid_model ==
                 FluidParameters::SolidModel::penalization_limit;
      }
      /// The grains act through constraints only, not in the assembly.
      bool
      constrains_solids() const
      {
        return rigid_nodes() || penalization_limit();
      }
      /// 'schur inner solver' with auto resolved: direct where the penalty
      /// sits in D = diag(A) (its contrast defeats the AMG on X), amg cg
      /// where X is a plain pressure Laplacian.
      SolverParameters::SchurInnerSolver
      schur_inner_solver() const
      {
        if (solver_parameters.schur_inner_solver !=
            SolverParameters::SchurInnerSolver::automatic)
          return solver_parameters.schur_inner_solver;
        return solid_field != nullptr &&
                   fluid_parameters.solid_model ==
                     FluidParameters::SolidModel::penalization ?
                 SolverParameters::SchurInnerSolver::direct :
                 SolverParameters::SchurInnerSolver::amg_cg;
      }
      /// The owned velocity DoFs that are constrained (grains' rigid
      /// nodes, walls, hanging nodes).
      IndexSet
      constrained_velocity_dofs() const;

      /// Locally owned DoFs (velocity and pressure) that the constraints fix.
      IndexSet
      owned_constrained_dofs() const;
      /// Rigid nodes, matrix-based solves: smooth the pressure of cells
      /// whose velocity nodes are (nearly) all imposed (see
      /// FluidParameters) rather than pin it. The matrix-free path has the
      /// block with the least-squares commutator only; with the
      /// Cahouet-Chabard block its steady solves keep the pins.
      bool
      smooth_solid_pressure() const
      {
        // Not rigid_nodes(): the sparsity is built before grains attach.
        return (fluid_parameters.solid_model ==
                  FluidParameters::SolidModel::rigid_nodes ||
                fluid_parameters.solid_model ==
                  FluidParameters::SolidModel::penalization_limit) &&
               fluid_parameters.rigid_node_pressure_smoothing > 0 &&
               (!use_matrix_free(Assembly::steady_stokes) ||
                solver_parameters.schur ==
                  SolverParameters::Schur::least_squares_commutator);
      }
      /// A cell with rigid nodes, of edge @p h, with @p n_rigid rigid and
      /// @p n_fixed imposed among its @p n_velocity velocity nodes: the
      /// factor of its Schur mass (its free fraction^4) and the weight of
      /// its rigid-node pressure smoothing (0 without the smoothing), as
      /// assemble() and the matrix-free path use them.
      std::pair<double, double>
      rigid_cell_weights(const unsigned int n_velocity,
                         const unsigned int n_rigid,
                         const unsigned int n_fixed,
                         const double       h) const
      {
        const double free_fraction =
          std::max(1e-4, std::pow(1. - double(n_rigid) / n_velocity, 4));
        const double smoothing =
          (smooth_solid_pressure() && n_rigid > 0) ?
            fluid_parameters.rigid_node_pressure_smoothing * h * h /
              fluid_parameters.viscosity *
              std::pow(double(n_fixed) / n_velocity, 4) :
            0.;
        return {free_fraction, smoothing};
      }
      /// Penalization limit: |int_K div t| h / (|K| U) of the blended
      /// targets t of the cell's constrained velocity nodes, U the larger
      /// of max_k |t_k| and mu / (rho h) (0 for one rigid translation or
      /// rotation; about 0 for solids at rest).
      double
      relative_target_divergence(
        const FEValues<dim>                        &fe_values,
        const std::vector<types::global_dof_index> &dof_indices,
        const std::vector<unsigned int>            &component,
        const double                                h) const;
      /// The hybrid model's porous coefficients of @p cell (none without
      /// solids or outside a porous zone).
      PorousCell<dim>
      porous_cell(const CellAccessor<dim, dim> &cell) const
      {
        return solid_field != nullptr ? solid_field->porous_cell(cell) :
                                        PorousCell<dim>();
      }
      /// Whether the penalization limit relaxes continuity where its
      /// targets squeeze or part the fluid (FluidParameters).
      bool
      relaxes_squeezes() const
      {
        return !limit_target.empty() &&
               fluid_parameters.squeeze_relaxation > 0;
      }
      /// The factor on a cut cell's pressure smoothing: 1 +
      /// squeeze relaxation * relative_target_divergence() where
      /// relaxes_squeezes(), else 1. @p fe_values: the cell's velocity
      /// gradients and JxW.
      double
      squeeze_factor(const FEValues<dim>                        &fe_values,
                     const std::vector<types::global_dof_index> &dof_indices,
                     const std::vector<unsigned int>            &component,
                     const double                                h) const
      {
        return relaxes_squeezes() ?
                 1. + fluid_parameters.squeeze_relaxation *
                        relative_target_divergence(fe_values,
                                                   dof_indices,
                                                   component,
                                                   h) :
                 1.;
      }
      /// Whether velocity dof @p i is imposed: rigid, Dirichlet, or hanging
      /// on rigid parents only (make_constraints() must have run).
      bool
      is_fixed_velocity(const types::global_dof_index i) const;
      /// Without the smoothing, a pressure node all of whose cells have
      /// every velocity node imposed meets no free velocity in div: pin it
      /// (p = 0) in #constraints (not yet closed).
      void
      pin_undetermined_solid_pressures();
      unsigned int
      solve_linear(const bool convection);
      /// (Re)build #preconditioner for the assembled system.
      void
      build_preconditioner(const bool convection, const IndexSet &constrained);
      /// The pressure-Laplacian coefficient 1/beta of the Schur
      /// approximation is capped where beta -> 0 (steady pure fluid) by
      /// this viscous scale mu / L^2 of the domain (both solve paths).
      double
      viscous_beta_floor() const;
      /// The message of an FGMRES that did not converge, for both paths.
      static std::string
      linear_solver_failure(const SolverControl::NoConvergence &e,
                            const double                       tolerance);
      /// Where the matrix-based system's residual at @p x is largest, in
      /// the momentum and in the continuity rows, for the failure message:
      /// a stalled solve is usually one place (a pocket between grains).
      std::string
      locate_largest_residual(const BlockVector &x) const;
      /// Shared tail of both linear solves: distribute the constraints into
      /// @p x, zero the mean pressure where no face fixes it, store it as
      /// the solution, check it is finite and count @p iterations.
      unsigned int
      accept_linear_solution(BlockVector &x, const unsigned int iterations);
      /// Call @p cell_action with the FEValues (Gauss points, @p flags) and
      /// the solid field of each locally owned cell with a covered point.
      void
      for_each_covered_cell(
        const UpdateFlags flags,
        const std::function<void(const FEValues<dim> &,
                                 const std::vector<double> &,
                                 const std::vector<Tensor<1, dim>> &,
                                 const std::vector<int> &)> &cell_action) const;
      /// The solid field at @p points of @p cell, with contact cells (see
      /// FluidParameters::free_contact_cells) left to the fluid.
      void
      evaluate_solids(const CellAccessor<dim, dim> &cell,
                      const std::vector<Point<dim>>  &points,
                      std::vector<double>            &void_fraction,
                      std::vector<Tensor<1, dim>>    &solid_velocity,
                      std::vector<int>               &solid_index) const;
      /// Whether contact cells are freed in this solve (FluidParameters::
      /// free_contact_cells: automatic frees them for moving grains in
      /// transient solves).
      bool
      frees_contact_cells() const;
      /// Whether @p cell touches a face with an imposed velocity or lies
      /// within one cell of two solids, and contact cells are freed.
      bool
      is_free_contact_cell(const CellAccessor<dim, dim> &cell) const;
      /// Mark the vertices on faces with an imposed velocity.
      void
      find_velocity_wall_vertices();
      /// The directional do-nothing term rho/2 |(w . n)_-| (u, v) of a
      /// traction face where fluid enters (kind's advecting velocity w).
      void
      add_inflow_traction(const FEFaceValuesBase<dim> &face_values,
                          const Assembly               kind,
                          const unsigned int           bdf_order,
                          FullMatrix<double>          &local_matrix) const;
      /// Penalty coefficient of the fixed-point (steady) Brinkman term.
      double
      brinkman_coefficient(const double void_fraction,
                           const double penalty_time_step) const;

      MPI_Comm                                   mpi_communicator;
      parallel::distributed::Triangulation<dim> &triangulation;
      const FluidParameters                     &fluid_parameters;
      const SolverParameters                    &solver_parameters;
      const BoundaryConditions<dim>             &boundary_conditions;
      ConditionalOStream                        &pcout;
      TimerOutput                               &timer;

      FESystem<dim>            fe;
      DoFHandler<dim>          dof_handler;
      AffineConstraints<double> constraints;
      std::vector<IndexSet>    owned_partitioning;
      std::vector<IndexSet>    relevant_partitioning;

      /// Matrix-free path: separate velocity (Q2^dim) and pressure (Q1)
      /// DoFHandlers whose indices equal the combined handler's block
      /// indices, and the solver state (matrix_free_stokes.cc).
      FESystem<dim>   fe_velocity;
      FE_Q<dim>       fe_pressure;
      DoFHandler<dim> dof_handler_velocity;
      DoFHandler<dim> dof_handler_pressure;
      struct MatrixFreeData;
      std::shared_ptr<MatrixFreeData> matrix_free_data;
      /// The transient matrix-free path's state, kept while the mesh is
      /// (transient_matrix_free.cc); reset by setup_dofs().
      struct TransientMatrixFree;
      std::shared_ptr<TransientMatrixFree> transient_matrix_free;

      TrilinosWrappers::BlockSparseMatrix system_matrix;
      /// Pressure blocks of the Schur complement approximation.
      TrilinosWrappers::BlockSparseMatrix pressure_mass_matrix;
      TrilinosWrappers::BlockSparseMatrix pressure_laplace_matrix;

      BlockVector solution, old_solution, older_solution;
      BlockVector system_rhs;

      /// The matrix-based preconditioner, kept over solves while the mesh
      /// and sparsity stay (SolverParameters::reuse_preconditioner); the
      /// kind of block it was built for and the iterations of its first
      /// solve. Declared after the matrices it refers to.
      std::unique_ptr<BlockSchurPreconditioner> preconditioner;
      bool                                      preconditioner_convection = false;
      unsigned int                              preconditioner_iterations = 0;
      /// constrained_velocity_dofs() when it was built: rigid nodes that
      /// grains entered or left change the matrix it approximates.
      IndexSet                                  preconditioner_constraints;
      IndexSet                                  pattern_constraints;
      /// AMG sweeps of the velocity block in use: 'velocity amg sweeps',
      /// doubled (at most twice) for the rest of the run each time a solve
      /// with a new preconditioner fails (solve_linear()).
      unsigned int velocity_amg_sweeps = 0;
      unsigned int
      velocity_amg_sweeps_in_use() const
      {
        return std::max(velocity_amg_sweeps,
                        solver_parameters.velocity_amg_sweeps);
      }

      const SolidField<dim>          *solid_field = nullptr;
      bool                             moving_solids = false;
      /// The system matrix holds entries between velocity components
      /// (stays true once a Newton step needed them).
      bool                             velocity_components_coupled = false;
      /// Per triangulation vertex: on a face with an imposed velocity.
      std::vector<bool>                velocity_wall_vertex;
      std::unique_ptr<
        parallel::distributed::SolutionTransfer<dim, BlockVector>>
        solution_transfer;
      std::unique_ptr<FunctionParser<dim>> body_force;
      double                           time              = 0;
      /// dt the reaction force refers to and whether it is a steady state.
      double                           last_time_step    = 1;
      unsigned int                     last_bdf_order    = 1;
      bool                             last_was_steady   = true;
      /// Pseudo-time cfl of the current Picard iteration (0: none).
      double                           pseudo_time_cfl   = 0;
      unsigned int                     steps_since_start = 0;
      /// The last advance() step, and its length over the one before (the
      /// step ratio of variable-step BDF2; 1 after BDF1).
      double                           previous_transient_step = 0;
      double                           bdf_step_ratio          = 1;
      SolveStatistics                  statistics;
      /// Rigid-node model: velocity dof -> grain whose rigid velocity it is
      /// constrained to, and the reactions (grain, node, force) of the
      /// last solve.
      std::unordered_map<types::global_dof_index, int> rigid_dof_grain;
      /// Penalization limit: the nodes whose target blends several grains,
      /// and each grain's share of the node's reaction.
      std::unordered_map<types::global_dof_index,
                         std::vector<std::pair<int, double>>>
        rigid_dof_shares;
      /// Penalization limit: each constrained node's blended target t_k.
      std::unordered_map<types::global_dof_index, double> limit_target;
      std::map<types::global_dof_index,
               std::vector<std::pair<types::global_dof_index, double>>>
        hanging_rigid_parents;
      std::vector<std::tuple<int, Point<dim>, Tensor<1, dim>>> rigid_reactions;
      double                           last_change = 0;
      Tensor<1, dim>                   last_boundary_force;
    };
  } // namespace fluid
} // namespace softsand

#endif
