#ifndef softsand_fluid_fluid_parameters_h
#define softsand_fluid_fluid_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * Fluid properties and the penalization parameter Theta of the paper's
     * Eq. (6): cells covered by solid carry density rho (1 + Theta (1 - vf)).
     */
    struct FluidParameters
    {
      double      density   = 1000;
      double      viscosity = 1e-3;
      double      theta     = 1e6;
      /// How grains act on the fluid: the paper's penalization (Eq. 6), a
      /// Theta -> infinity limit with velocity nodes inside grains
      /// constrained to the grain's rigid velocity, or the limit of the
      /// penalized update itself node by node (penalization_limit.h).
      enum class SolidModel
      {
        penalization,
        rigid_nodes,
        penalization_limit
      };
      SolidModel solid_model = SolidModel::penalization;
      /// Rigid nodes: nodes within radius + offset * (node spacing) of a
      /// grain centre are constrained (dimensionless offset).
      double rigid_node_offset = 0.25;
      /// Rigid nodes: weight alpha of the pressure Laplacian, alpha h^2 / mu
      /// times (imposed fraction of the cell's velocity nodes)^4, added to
      /// the continuity rows of cells with rigid nodes, so that pressure
      /// modes no free velocity sees stay smooth (dimensionless; 0: pin
      /// the pressure of wholly imposed cells instead).
      double rigid_node_pressure_smoothing = 1e-4;
      /// Penalization limit: the smoothing of a cell grows by 1 + this
      /// factor times the relative divergence of its nodes' blended
      /// targets (two solids approaching, parting or turning against each
      /// other; zero for one rigid motion and for solids at rest).
      double squeeze_relaxation = 100;
      /// Penalization: constrain the velocity nodes of cells wholly inside
      /// a grain (the Theta -> infinity limit there), penalize cut cells.
      bool constrain_grain_interiors = true;
      /// Cells where two solids, or a solid and a velocity wall, would
      /// impose conflicting motions: left to the fluid (yes), kept (no), or
      /// left to the fluid when the solids move (automatic).
      enum class FreeContactCells
      {
        automatic,
        yes,
        no
      };
      FreeContactCells free_contact_cells = FreeContactCells::automatic;
      /// Body force per unit volume (N/m^3), a function of x, y, z, t.
      std::string body_force = "0; 0; 0";

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };


    /**
     * Nonlinear and linear solver settings of the penalized Navier-Stokes
     * system.
     */
    struct SolverParameters
    {
      enum class Nonlinear
      {
        newton,
        picard
      };
      /// Schur complement approximation of the block preconditioner.
      enum class Schur
      {
        cahouet_chabard,
        discrete_brinkman,
        least_squares_commutator,
        weighted_mass,
        mass
      };
      /// How the linear systems are stored and preconditioned.
      enum class LinearSolver
      {
        matrix_based,
        matrix_free
      };
      Nonlinear    nonlinear_method         = Nonlinear::newton;
      double       nonlinear_tolerance      = 1e-8;
      unsigned int max_nonlinear_iterations = 30;
      double       linear_tolerance         = 1e-8;
      unsigned int max_linear_iterations    = 1000;
      /// Krylov vectors kept by FGMRES before it restarts.
      unsigned int krylov_restart           = 100;
      Schur        schur                    = Schur::least_squares_commutator;
      /// schur = discrete brinkman or least squares commutator: relative
      /// tolerance of the inner CG on B D^-1 B^T.
      double       schur_inner_tolerance    = 1e-6;
      /// How those inner solves on X = B D^-1 B^T + C are made; automatic
      /// is resolved by the solver (direct with penalization).
      enum class SchurInnerSolver
      {
        automatic,
        direct,
        amg_cg
      };
      SchurInnerSolver schur_inner_solver = SchurInnerSolver::automatic;
      /// Keep the preconditioner of the last solve while the mesh and the
      /// matrix sparsity are unchanged (coupling steps); a solve that would
      /// need more than 'rebuild factor' times the iterations of the solve
      /// it was built for (+ 5) is stopped there and redone with a new one.
      bool         reuse_preconditioner     = true;
      double       preconditioner_rebuild_factor = 1.5;
      unsigned int velocity_amg_sweeps      = 4;
      /// Smoother of the velocity-block AMG (an ML smoother type).
      enum class AmgSmoother
      {
        /// ilu for a block with convection, chebyshev without.
        automatic,
        chebyshev,
        symmetric_gauss_seidel,
        ilu
      };
      AmgSmoother velocity_amg_smoother = AmgSmoother::automatic;
      /// Smoothed aggregation (ML's default) instead of plain aggregation
      /// in the velocity-block AMG: denser coarse levels, slower setup.
      bool velocity_amg_smoothed_aggregation = false;
      /// Matrix based: a sparse direct solve of the velocity block in the
      /// preconditioner instead of the AMG V-cycle.
      bool direct_velocity_solve = false;
      /// Grad-div coefficient gamma (Pa s): gamma (div v, div u) in the
      /// momentum equation, and mu + gamma in the Schur approximation.
      double grad_div = 0;
      /// Cell part of gamma: + factor rho |u| h (dimensionless factor).
      double grad_div_cell_factor = 0;
      /// Steady Navier-Stokes: pseudo-time continuation of the Picard
      /// iterations, a term rho |w| / (cfl h) (u_{k+1} - u_k) at each point
      /// of a cell of edge h (0: plain Picard).
      double pseudo_time_cfl = 0;
      /// Growth of that cfl per Picard iteration once the change falls.
      double pseudo_time_growth = 2;
      LinearSolver linear_solver            = LinearSolver::matrix_based;
      /// The solver of the transient model's steps (advance()), when the
      /// user chose one; automatic: PenalizedNavierStokes decides from the
      /// solid model (transient_solver is then not read).
      LinearSolver transient_solver           = LinearSolver::matrix_based;
      bool         transient_solver_automatic = true;
      /// Geometric multigrid of the matrix-free velocity block.
      unsigned int smoother_degree = 4;
      double       smoothing_range = 20;
      /// Matrix free: geometric levels below Q1 (else AMG on assembled Q1).
      bool         multigrid_geometric_levels = false;
      /// Matrix free: relative tolerance of the coarse (Q1) solve.
      double       multigrid_coarse_tolerance = 1e-3;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace fluid
} // namespace softsand

#endif
