#include <softsand/base/parameter_tools.h>
#include <softsand/fluid/fluid_parameters.h>

#include <cmath>

namespace softsand
{
  namespace fluid
  {
    void
    FluidParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("fluid");
      prm.declare_entry("density",
                        "1000",
                        Patterns::Double(0),
                        "Fluid density rho (kg/m^3).");
      prm.declare_entry("viscosity",
                        "1e-3",
                        Patterns::Double(0),
                        "Dynamic viscosity mu (Pa s).");
      prm.declare_entry("theta",
                        "1e6",
                        Patterns::Double(0, 1e16),
                        "Penalization Theta (dimensionless): density "
                        "rho (1 + Theta (1 - vf)) where grains cover the "
                        "fluid (the paper's Eq. 6; converged by 1e6).");
      prm.declare_entry(
        "solid model",
        "penalization",
        Patterns::Selection("penalization|rigid nodes|penalization limit"),
        "penalization: the paper's Eq. 6, density rho (1 + Theta (1 - vf)) "
        "and the grain velocity in the momentum predictor; rigid nodes: its "
        "Theta -> infinity limit, velocity nodes inside grains constrained "
        "to the grain's rigid velocity (sharper surface at the node spacing "
        "h/2, and a linear system free of the penalty's ill-conditioning); "
        "penalization limit: the Theta -> infinity limit of the paper's "
        "penalized update with its void fraction, node by node: each "
        "velocity node of a covered cell gets one target, the average of "
        "the rigid velocities of the grains over it in the cells around it "
        "weighted by their covered part, and is constrained to u = vf u_old "
        "+ (1 - vf) target (vf: the node's void fraction from the cells' "
        "void fractions; steady solves: u = target); the fluid force on "
        "each grain is the reaction of those rows, split by the same "
        "weights. A node never follows two rigid motions, so Theta drops "
        "out: the coupled injection at 4 cells per diameter is stable where "
        "penalization at Theta >= 1e4 is not (doc/hele_shaw.md). Matrix-"
        "based solvers only; the rigid node pressure smoothing applies.");
      prm.declare_entry(
        "rigid node offset",
        "0.25",
        Patterns::Double(-1, 1),
        "solid model = rigid nodes: constrain the velocity nodes within "
        "radius + offset * (node spacing) of a grain centre "
        "(dimensionless). The no-slip surface of a node staircase lies inside "
        "the outermost constrained nodes; 0.25 puts it on the sphere in the "
        "Stokes drag study at 4 and 8 cells per diameter (doc/validation.md), "
        "0 constrains the nodes inside the grain only.");
      prm.declare_entry(
        "rigid node pressure smoothing",
        "1e-4",
        Patterns::Double(0, 1),
        "solid model = rigid nodes or penalization limit: in cells whose "
        "velocity nodes are all or "
        "nearly all imposed (inside a grain, between two grains closer than "
        "a cell, or a grain and a no-slip wall) the continuity equation "
        "meets too few free velocities and leaves pressure modes "
        "undetermined; they act on the solids as pair forces of the ambient "
        "pressure times about a node area (two grains 0.1 mm apart at 4 "
        "cells per mm in a uniform 1 kPa: 3.5e-5 N each; the 250-grain "
        "Hele-Shaw pack in a uniform 4 kPa: up to 170 grain weights). This "
        "weight alpha adds alpha h^2 / mu times the cell's imposed fraction "
        "of velocity nodes to the fourth power times the pressure Laplacian "
        "to the continuity equation of those cells (dimensionless, 0-1): "
        "the solids' pressure continues the fluid's smoothly and a uniform "
        "pressure exerts no force. It also lets fluid through the throats "
        "between touching grains: on that pack's permeability +0.2 / 1.5 / "
        "7 / 31 % at 1e-5 / 1e-4 / 1e-3 / 1e-2, the largest force in the "
        "uniform pressure 44 / 0.3 / - / 0.05 weights. 0: pin the pressure "
        "of wholly imposed cells to 0 and leave the rest (steady solves on "
        "the matrix-free path always do).");
      prm.declare_entry(
        "squeeze relaxation",
        "100",
        Patterns::Double(0, 1e6),
        "solid model = penalization limit: where the blended targets of a "
        "cell's velocity nodes are not divergence free (two grains, or a "
        "grain and a wall, approaching, parting or turning against each "
        "other in the cells they share), the imposed velocities contradict "
        "continuity and the squeezed fluid has no free node to leave by; "
        "the cell's pressure then carries the contradiction to the grains "
        "as forces 50-70 times the rigid nodes' (tests/paper_model_contact, "
        "two touching grains approaching at 0.1 m/s). The cell's rigid node "
        "pressure smoothing is multiplied by 1 + this factor times "
        "|int_K div t| h / (|K| U), t the blended targets (a node without one: "
        "its rigid parents' if it hangs on them, its imposed value on a "
        "wall, else the cell's mean target) and U the larger "
        "of max |t| and the cell's viscous velocity mu / (rho h) "
        "(dimensionless): the same test's forces come within 1.7 times the "
        "rigid nodes' at 100. One rigid motion is untouched and grains much "
        "slower than mu / (rho h) count as at rest (the small Hele-Shaw "
        "pack's permeability moves by 0.1 %). 0: the smoothing alone.");
      prm.declare_entry(
        "constrain grain interiors",
        "true",
        Patterns::Bool(),
        "solid model = penalization: constrain the velocity nodes of cells "
        "wholly inside a grain to its rigid velocity (the Theta -> infinity "
        "limit there) so that the penalty acts in cut cells only; false: "
        "penalize every covered cell as in the paper.");
      prm.declare_entry(
        "free contact cells",
        "automatic",
        Patterns::Selection("automatic|true|false"),
        "Leave to the fluid (void fraction 1, no imposed grain velocity) the "
        "cells that touch a wall with an imposed velocity and the cells "
        "within one cell of two grains. There the rigid motions the solids "
        "impose conflict (a grain moving into or along a no-slip wall, two "
        "touching grains moving apart), and the solid model turns the "
        "conflict into a fictitious force of order rho Theta / dt times the "
        "relative velocity; the free layer carries a resolved lubrication "
        "flow instead, and the contact itself is the DEM's. The freed cells "
        "are a cell thick: on meshes of a few cells per diameter they take "
        "a large part of a dense pack's grains away from the fluid (the "
        "2,000-grain Hele-Shaw pack at 2 cells per diameter: permeability "
        "100x). automatic: true for moving grains in the transient fluid "
        "model (where the held penalty reaction drove grains at walls to "
        "NaN), false in the quasi-steady model (the measured resistance "
        "keeps those grains stable) and for fixed grains.");
      prm.declare_entry("body force",
                        "0; 0; 0",
                        Patterns::Anything(),
                        "Body force per unit volume (N/m^3): one expression "
                        "in x, y, z, t per component, separated by ';'.");
      prm.leave_subsection();
    }


    void
    FluidParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("fluid");
      density   = prm.get_double("density");
      viscosity = prm.get_double("viscosity");
      theta     = prm.get_double("theta");
      body_force = prm.get("body force");
      rigid_node_offset = prm.get_double("rigid node offset");
      rigid_node_pressure_smoothing =
        prm.get_double("rigid node pressure smoothing");
      squeeze_relaxation = prm.get_double("squeeze relaxation");
      constrain_grain_interiors = prm.get_bool("constrain grain interiors");
      const std::string free_contact = prm.get("free contact cells");
      free_contact_cells = free_contact == "automatic" ?
                             FreeContactCells::automatic :
                             (free_contact == "true" ? FreeContactCells::yes :
                                                       FreeContactCells::no);
      const std::string model = prm.get("solid model");
      solid_model = model == "rigid nodes"        ? SolidModel::rigid_nodes :
                    model == "penalization limit" ?
                                                    SolidModel::penalization_limit :
                                                    SolidModel::penalization;
      if (!(density > 0))
        base::throw_invalid_parameter("fluid/density",
                                      prm.get("density"),
                                      "the density must be > 0 kg/m^3");
      if (!(viscosity > 0))
        base::throw_invalid_parameter("fluid/viscosity",
                                      prm.get("viscosity"),
                                      "the viscosity must be > 0 Pa s");
      prm.leave_subsection();
    }


    void
    SolverParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("fluid solver");
      prm.declare_entry("nonlinear method",
                        "newton",
                        Patterns::Selection("newton|picard"),
                        "Linearization of the steady convection term. "
                        "newton: the convective form rho (u . grad) u, "
                        "quadratic convergence near the solution; picard: "
                        "Oseen iterations in Temam's skew-symmetric form "
                        "(rho (w . grad) u + rho/2 (div w) u, energy-stable, "
                        "as the transient model), with the pseudo-time "
                        "continuation of 'pseudo time cfl'. The two forms "
                        "differ by the discrete divergence error.");
      prm.declare_entry("nonlinear tolerance",
                        "1e-8",
                        Patterns::Double(0, 1),
                        "Steady Navier-Stokes stops when ||u_k+1 - u_k|| / "
                        "||u_k+1|| is below this (dimensionless).");
      prm.declare_entry("max nonlinear iterations",
                        "30",
                        Patterns::Integer(1),
                        "Upper bound on Newton/Picard iterations.");
      prm.declare_entry("linear tolerance",
                        "1e-8",
                        Patterns::Double(0, 1),
                        "FGMRES stops at this residual relative to the "
                        "right-hand side (dimensionless).");
      prm.declare_entry("max linear iterations",
                        "1000",
                        Patterns::Integer(1),
                        "Upper bound on FGMRES iterations per solve.");
      prm.declare_entry("krylov restart",
                        "100",
                        Patterns::Integer(10, 2000),
                        "FGMRES keeps this many search directions before it "
                        "restarts: more converge faster on hard systems "
                        "(dense penalized packs) at 2 vectors of memory "
                        "each.");
      prm.declare_entry(
        "schur complement",
        "least squares commutator",
        Patterns::Selection(
          "cahouet chabard|discrete brinkman|least squares commutator|"
          "weighted mass|mass"),
        "Pressure Schur complement approximation: cahouet chabard = "
        "mu M_p^-1 + (-div (1/beta) grad)^-1 with beta the "
        "penalty/inertia coefficient at each quadrature point (robust in "
        "Theta around isolated grains); discrete brinkman = mu M_p^-1 + "
        "(B D^-1 B^T)^-1 with D the diagonal of the assembled velocity "
        "block, solved by CG + AMG to 'schur inner tolerance' (dense "
        "packs: a pore closed by grains stays closed in D, where the "
        "quadrature-point Laplacian leaks through cut cells; switches to "
        "the matrix-based solver); least squares commutator = "
        "X^-1 (B D^-1 A D^-1 B^T + C) X^-1 with X = B D^-1 B^T + C, C the "
        "rigid-node pressure smoothing (diagonally scaled BFBT: the Darcy "
        "limit inside grains, the commutator in the fluid, convection "
        "included; two inner CG solves; matrix based or matrix free); "
        "weighted mass = mass matrix weighted "
        "by 1/(mu + beta h^2); mass = 1/mu mass matrix (plain Stokes).");
      prm.declare_entry("schur inner tolerance",
                        "1e-6",
                        Patterns::Double(1e-12, 0.5),
                        "schur complement = discrete brinkman or least "
                        "squares commutator: relative tolerance of the "
                        "inner CG on B D^-1 B^T (dimensionless). 1e-2 gave "
                        "7x more FGMRES iterations on a dense pack than "
                        "1e-4 (discrete brinkman); the commutator, which "
                        "applies it twice, stalled at 1e-4 on a "
                        "simple-cubic array and converges at 1e-6 "
                        "(doc/notes/solver_study.md).");
      prm.declare_entry(
        "schur inner solver",
        "auto",
        Patterns::Selection("auto|direct|amg cg"),
        "schur complement = discrete brinkman or least squares commutator: "
        "how X = B D^-1 B^T + C is inverted. direct = a sparse LU "
        "factorization (MUMPS), made once per preconditioner and exact "
        "whatever the penalty contrast and the pores sealed at the "
        "resolution; its memory and time grow faster than the pressure "
        "unknowns. It falls back to amg cg, with a warning, where X is "
        "singular (a mesh too coarse for its walls) or MUMPS's estimate of "
        "its memory exceeds half the memory available on a rank. amg cg = "
        "CG with an AMG V-cycle to 'schur inner tolerance', stopped at 200 "
        "iterations: memory linear in the unknowns, and a few iterations "
        "where X is a plain pressure Laplacian (rigid nodes), but on "
        "penalized packs the penalty's contrast in D makes it reach that "
        "bound. auto = direct with fluid/solid model = penalization, amg cg "
        "otherwise (doc/notes/solver_study.md: Fig. 3 pack at N = 8, 5x faster "
        "with direct; Hele-Shaw with rigid nodes at 4.4 M DoFs, the same "
        "time and half the memory with amg cg).");
      prm.declare_entry(
        "reuse preconditioner",
        "true",
        Patterns::Bool(),
        "Keep the preconditioner (AMG hierarchies, Schur blocks) of the "
        "last matrix-based solve while the mesh and the matrix sparsity are "
        "unchanged, e.g. over coupling steps whose grains moved less than a "
        "cell; FGMRES stays exact, only its iteration count can grow.");
      prm.declare_entry(
        "preconditioner rebuild factor",
        "1.5",
        Patterns::Double(1),
        "reuse preconditioner = true: a solve with a kept preconditioner "
        "that needs more than this factor times the iterations of the "
        "solve it was built for (plus 5) is stopped there and redone from "
        "the same start with a new preconditioner (dimensionless).");
      prm.declare_entry("velocity amg sweeps",
                        "4",
                        Patterns::Integer(1, 10),
                        "linear solver = matrix based: smoother sweeps of the "
                        "velocity-block AMG. A solve that fails with a new "
                        "preconditioner is retried with twice the sweeps (at "
                        "most four times this value), kept for the rest of "
                        "the run, with a warning.");
      prm.declare_entry(
        "velocity amg smoother",
        "auto",
        Patterns::Selection("auto|chebyshev|symmetric gauss seidel|ilu"),
        "Smoother of the velocity-block AMG (ML). chebyshev assumes a "
        "symmetric positive definite block (Stokes); ilu (incomplete LU "
        "per rank) also smooths the nonsymmetric convection block of "
        "transient and Picard/Newton steps: on the small Hele-Shaw "
        "injection at 16 kPa (transient, cell Reynolds numbers near 100) "
        "it took 3-19 FGMRES iterations per step where chebyshev took "
        "65-212 and symmetric gauss seidel 483 (doc/notes/solver_study.md, "
        "\"The velocity smoother of convective steps\"); symmetric gauss "
        "seidel is kept for the steady drag studies at Re = 50 and 100 "
        "(doc/validation.md). auto: ilu where the block carries "
        "convection, chebyshev for Stokes.");
      prm.declare_entry(
        "velocity amg aggregation",
        "plain",
        Patterns::Selection("plain|smoothed"),
        "linear solver = matrix based: how the velocity-block AMG (ML) "
        "builds its coarse levels. plain = piecewise-constant aggregates; "
        "smoothed = ML's default, one Jacobi step on them, which makes the "
        "coarse matrices denser (103 nonzeros per row on the small "
        "Hele-Shaw cell against 29 on the fine level). plain set up 1.6x "
        "faster with 11 % less memory on the Fig. 3 pack at N = 6 (24 "
        "FGMRES iterations against 21, same K) and took 6-9 instead of "
        "7-10 on the Hele-Shaw cell (doc/notes/solver_study.md, \"Plain "
        "aggregation\").");
      prm.declare_entry(
        "velocity block solver",
        "amg",
        Patterns::Selection("amg|direct"),
        "linear solver = matrix based: how the preconditioner applies the "
        "inverse of the velocity block. amg: one ML V-cycle (the default); "
        "direct: a sparse LU factorization (Amesos), exact but with memory "
        "and time growing much faster than the unknowns, for problems of "
        "up to some 1e5 free velocity unknowns. An Oseen block at cell "
        "Reynolds numbers of tens to hundreds is where the V-cycle fails "
        "and the factorization does not (doc/notes/solver_study.md, \"Oseen\").");
      prm.declare_entry(
        "grad div",
        "0",
        Patterns::Double(0),
        "Grad-div coefficient gamma (Pa s): adds gamma (div v, div u) to "
        "the momentum equation (consistent: div u = 0 for the exact "
        "solution) and uses mu + gamma in the pressure-mass Schur "
        "approximation (deal.II step-57). Steady flow at Re >~ 10 needs "
        "it for FGMRES to converge: gamma = rho U d (Re mu) with 'grad div "
        "cell factor' = 1 for the sphere at Re = 10 to 100; 0 = off.");
      prm.declare_entry(
        "grad div cell factor",
        "0",
        Patterns::Double(0),
        "Dimensionless factor c of a cell part of the grad-div coefficient: "
        "gamma = 'grad div' + c rho |u| h at each point of a cell of edge "
        "h, with u the advecting velocity. The Schur complement of the "
        "convective block scales like (rho |u| h)^-1 M_p in cells with a "
        "cell Reynolds number above 1, so coarse far-field cells need a "
        "larger gamma than the grain's cells: with a fixed gamma = rho U d "
        "FGMRES stalled in a 40 d box at Re = 10 and 50, c = 1 converges "
        "(doc/validation.md). 0 = constant gamma.");
      prm.declare_entry(
        "pseudo time cfl",
        "0",
        Patterns::Double(0),
        "Steady Navier-Stokes (and the quasi-steady Navier-Stokes coupling "
        "model): each Picard iteration adds the pseudo-time term "
        "rho |w| / (cfl h) (u_{k+1} - u_k) at each point of a cell of edge "
        "h, w the previous iterate. It vanishes at convergence, so the "
        "steady solution is unchanged; it makes the convective velocity "
        "block diagonally dominant at high cell Reynolds numbers, where "
        "plain Picard's linear solves do not converge. 0 = plain Picard.");
      prm.declare_entry(
        "pseudo time growth",
        "2",
        Patterns::Double(1),
        "Factor by which 'pseudo time cfl' grows after each Picard "
        "iteration whose change fell (switched evolution relaxation).");
      prm.declare_entry(
        "linear solver",
        "matrix based",
        Patterns::Selection("matrix free|matrix based"),
        "matrix free: FGMRES on the matrix-free Q2-Q1 operator, velocity "
        "block preconditioned by one geometric multigrid V-cycle (Q2, then "
        "Q1 on the globally coarsened meshes); matrix based: Trilinos "
        "matrices, velocity block by one ML AMG V-cycle. Both use the "
        "Schur complement approximation below; matrix free assembles only "
        "Q1 matrices (with the least squares commutator, peak memory 933 "
        "instead of 1,479 MB on the 2-cell Hele-Shaw cell, doc/notes/solver_study.md). Solves with convection "
        "(Navier-Stokes, transient) and grad-div are matrix based.");
      prm.declare_entry(
        "transient solver",
        "auto",
        Patterns::Selection("auto|matrix free|matrix based"),
        "The solver of the transient model's time steps (Navier-Stokes with "
        "BDF, the coupled injections). auto: matrix free in 3D with "
        "fluid/solid model = rigid nodes or penalization limit and no grad "
        "div, where it is "
        "measured faster (in 2D its FGMRES stalls near 1e-7 on the "
        "convergence study's channel); "
        "matrix based with the penalization, whose contrast in the "
        "velocity block's diagonal slows the matrix-free path's Schur "
        "solve (doc/notes/solver_study.md). matrix based: the system assembled "
        "into Trilinos matrices at every step, velocity block by ML AMG with "
        "ILU smoothing, the least-squares commutator (above); matrix free: "
        "the same discrete step with the Q2-Q1 operator applied cell by "
        "cell on a MatrixFree object kept while the mesh is, the grains' "
        "rigid nodes as identity rows of the step, cells whose velocity "
        "nodes are all imposed skipped, FGMRES preconditioned by "
        "Jacobi-GMRES on the mass-dominated velocity block and CG + AMG on "
        "X = B D^-1 B^T + C (B assembled once per mesh); the fluid force on "
        "the grains from the residual of their rows, no second assembly. "
        "Less memory and setup, more Krylov work: which is faster depends "
        "on the scene and the step (doc/notes/solver_study.md, \"The transient "
        "matrix-free step\"). Not with grad div.");
      prm.declare_entry("multigrid smoother degree",
                        "4",
                        Patterns::Integer(1, 20),
                        "linear solver = matrix free: degree of the "
                        "Chebyshev smoother (matrix-vector products per "
                        "pre- or post-smoothing) on each multigrid level.");
      prm.declare_entry("multigrid smoothing range",
                        "20",
                        Patterns::Double(1.01, 1000),
                        "linear solver = matrix free: the Chebyshev smoother "
                        "damps eigenvalues from lambda_max / range to "
                        "lambda_max of the Jacobi-scaled level operator "
                        "(dimensionless).");
      prm.declare_entry(
        "multigrid coarse levels",
        "algebraic",
        Patterns::Selection("algebraic|geometric"),
        "linear solver = matrix free: below the Q2 level, algebraic = Q1 "
        "on the same (active) mesh, solved by CG with ML AMG on its "
        "assembled matrix; geometric = Q1 on every globally coarsened "
        "mesh, AMG on the coarsest. A geometric coarse mesh penalizes every "
        "cell a grain cuts and so sees fatter grains: one sphere at Theta "
        "1e12, N = 12 took 922 FGMRES iterations with geometric levels "
        "(doc/notes/solver_study.md).");
      prm.declare_entry("multigrid coarse tolerance",
                        "1e-3",
                        Patterns::Double(1e-12, 0.9),
                        "linear solver = matrix free: relative tolerance of "
                        "the CG + AMG solve on the coarsest level "
                        "(dimensionless).");
      prm.leave_subsection();
    }


    void
    SolverParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("fluid solver");
      nonlinear_method = prm.get("nonlinear method") == "newton" ?
                           Nonlinear::newton :
                           Nonlinear::picard;
      nonlinear_tolerance      = prm.get_double("nonlinear tolerance");
      max_nonlinear_iterations = prm.get_integer("max nonlinear iterations");
      linear_tolerance         = prm.get_double("linear tolerance");
      max_linear_iterations    = prm.get_integer("max linear iterations");
      krylov_restart           = prm.get_integer("krylov restart");
      const std::string s      = prm.get("schur complement");
      schur = s == "cahouet chabard"   ? Schur::cahouet_chabard :
              s == "discrete brinkman" ? Schur::discrete_brinkman :
              s == "least squares commutator" ?
                                         Schur::least_squares_commutator :
              s == "weighted mass"     ? Schur::weighted_mass :
                                       Schur::mass;
      schur_inner_tolerance = prm.get_double("schur inner tolerance");
      const std::string inner = prm.get("schur inner solver");
      schur_inner_solver      = inner == "auto"   ? SchurInnerSolver::automatic :
                                inner == "direct" ? SchurInnerSolver::direct :
                                                    SchurInnerSolver::amg_cg;
      reuse_preconditioner  = prm.get_bool("reuse preconditioner");
      preconditioner_rebuild_factor =
        prm.get_double("preconditioner rebuild factor");
      velocity_amg_sweeps = prm.get_integer("velocity amg sweeps");
      {
        const std::string smoother = prm.get("velocity amg smoother");
        velocity_amg_smoother =
          smoother == "auto"      ? AmgSmoother::automatic :
          smoother == "chebyshev" ? AmgSmoother::chebyshev :
          smoother == "ilu"       ? AmgSmoother::ilu :
                                    AmgSmoother::symmetric_gauss_seidel;
      }
      velocity_amg_smoothed_aggregation =
        prm.get("velocity amg aggregation") == "smoothed";
      direct_velocity_solve = prm.get("velocity block solver") == "direct";
      grad_div              = prm.get_double("grad div");
      grad_div_cell_factor     = prm.get_double("grad div cell factor");
      if (!(grad_div >= 0) || !std::isfinite(grad_div))
        base::throw_invalid_parameter("fluid solver/grad div",
                                      prm.get("grad div"),
                                      "gamma must be a finite value >= 0 "
                                      "Pa s");
      pseudo_time_cfl    = prm.get_double("pseudo time cfl");
      pseudo_time_growth = prm.get_double("pseudo time growth");
      linear_solver            = prm.get("linear solver") == "matrix free" ?
                                   LinearSolver::matrix_free :
                                   LinearSolver::matrix_based;
      transient_solver_automatic = prm.get("transient solver") == "auto";
      transient_solver         = prm.get("transient solver") == "matrix free" ?
                                   LinearSolver::matrix_free :
                                   LinearSolver::matrix_based;
      if (transient_solver == LinearSolver::matrix_free &&
          (grad_div > 0 || grad_div_cell_factor > 0))
        base::throw_invalid_parameter(
          "fluid solver/transient solver",
          prm.get("transient solver"),
          "the matrix-free transient step has no grad-div term: set 'grad "
          "div' and 'grad div cell factor' to 0 or use 'matrix based'");
      smoother_degree          = prm.get_integer("multigrid smoother degree");
      smoothing_range          = prm.get_double("multigrid smoothing range");
      multigrid_geometric_levels =
        prm.get("multigrid coarse levels") == "geometric";
      multigrid_coarse_tolerance =
        prm.get_double("multigrid coarse tolerance");
      prm.leave_subsection();
    }
  } // namespace fluid
} // namespace softsand
