// The matrix-free path of PenalizedNavierStokes: FGMRES on the Q2-Q1
// operator applied cell by cell (sum factorization), the velocity block
// preconditioned by one geometric multigrid V-cycle, the Schur complement by
// the same approximations as the matrix-based path: the least-squares
// commutator X^-1 (B D^-1 A D^-1 B^T + C) X^-1 with A and B applied matrix
// free and only Q1 pressure matrices assembled (X = B D^-1 B^T + C, the
// rigid-node smoothing C; about a 25th of the unknowns), or Cahouet-Chabard
// (two assembled Q1 pressure matrices).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/matrix_free/fe_evaluation.h>

#include <deal.II/numerics/vector_tools.h>

#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/matrix_free_operators.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/fluid/velocity_multigrid.h>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    struct PenalizedNavierStokes<dim>::MatrixFreeData
    {
      MappingQ1<dim>                                     mapping;
      AffineConstraints<double>                          velocity_constraints;
      AffineConstraints<double>                          pressure_constraints;
      std::shared_ptr<MatrixFree<dim, double>>           matrix_free;
      std::shared_ptr<VelocityCoefficients<dim, double>> coefficients;
      std::shared_ptr<VelocityOperator<dim, 2, double>>  velocity_operator;
      StokesOperator<dim>                                stokes;
      VelocityMultigrid<dim>                             multigrid;
      TrilinosWrappers::SparseMatrix                     pressure_mass;
      TrilinosWrappers::SparseMatrix                     pressure_laplace;
      TrilinosWrappers::PreconditionILU                  pressure_mass_ilu;
      TrilinosWrappers::PreconditionAMG                  pressure_laplace_amg;
      /// Least-squares commutator: X = B D^-1 B^T + C, its AMG, D^-1.
      TrilinosWrappers::SparseMatrix                     discrete_brinkman;
      DiscreteBrinkmanSolver                             discrete_brinkman_inverse;
      LinearAlgebra::distributed::Vector<double>         inverse_diagonal;
      /// Rigid-node pressure smoothing: the pressure block -C.
      TrilinosWrappers::SparseMatrix                     pressure_block;
    };


    namespace
    {
      /**
       * Block upper-triangular preconditioner of the matrix-free path:
       * p = -S~^-1 r_p, then one multigrid V-cycle for u from r_u - B^T p.
       * S~^-1 is either M_p(1/mu)^-1 + L_p(1/beta)^-1 (Cahouet-Chabard) or
       * the least-squares commutator X^-1 (B D^-1 A D^-1 B^T + C) X^-1 (see
       * BlockSchurPreconditioner); constrained pressure rows are identity
       * rows of the operator, so their block is the identity.
       */
      template <int dim>
      class MatrixFreeBlockPreconditioner
      {
      public:
        using VectorType      = LinearAlgebra::distributed::Vector<double>;
        using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

        MatrixFreeBlockPreconditioner(
          const StokesOperator<dim>               &stokes,
          const VelocityMultigrid<dim>            &multigrid,
          const TrilinosWrappers::PreconditionILU &pressure_mass,
          const TrilinosWrappers::PreconditionAMG *pressure_laplace)
            : stokes(stokes)
            , multigrid(multigrid)
            , pressure_mass(&pressure_mass)
            , pressure_laplace(pressure_laplace)
        {}

        /// The least-squares commutator.
        MatrixFreeBlockPreconditioner(
          const StokesOperator<dim>                   &stokes,
          const VelocityMultigrid<dim>                &multigrid,
          const VelocityOperator<dim, 2, double>      &velocity,
          const DiscreteBrinkmanSolver                &discrete_brinkman,
          const VectorType                            &inverse_diagonal,
          const TrilinosWrappers::SparseMatrix        *pressure_block,
          const std::vector<unsigned int>             &constrained_pressure)
            : stokes(stokes)
            , multigrid(multigrid)
            , velocity(&velocity)
            , discrete_brinkman(&discrete_brinkman)
            , inverse_diagonal(&inverse_diagonal)
            , pressure_block(pressure_block)
            , constrained_pressure(&constrained_pressure)
        {}

        void
        vmult(BlockVectorType &dst, const BlockVectorType &src) const
        {
          if (discrete_brinkman != nullptr)
            apply_commutator(dst.block(1), src.block(1));
          else
            {
              pressure_mass->vmult(dst.block(1), src.block(1));
              if (pressure_laplace != nullptr)
                {
                  tmp_p.reinit(src.block(1), true);
                  pressure_laplace->vmult(tmp_p, src.block(1));
                  dst.block(1) += tmp_p;
                }
              dst.block(1) *= -1.;
            }
          tmp_u.reinit(src.block(0), true);
          stokes.apply_gradient(tmp_u, dst.block(1));
          tmp_u.sadd(-1., 1., src.block(0));
          multigrid.vmult(dst.block(0), tmp_u);
        }

      private:
        const StokesOperator<dim>               &stokes;
        const VelocityMultigrid<dim>            &multigrid;
        const TrilinosWrappers::PreconditionILU *pressure_mass    = nullptr;
        const TrilinosWrappers::PreconditionAMG *pressure_laplace = nullptr;
        const VelocityOperator<dim, 2, double>  *velocity         = nullptr;
        const DiscreteBrinkmanSolver            *discrete_brinkman = nullptr;
        const VectorType                        *inverse_diagonal     = nullptr;
        const TrilinosWrappers::SparseMatrix    *pressure_block       = nullptr;
        const std::vector<unsigned int>         *constrained_pressure = nullptr;
        mutable VectorType                       tmp_u, tmp_u2, tmp_p, tmp_p2;

        /// dst = -X^-1 (B D^-1 A D^-1 B^T + C) X^-1 src on coupled rows.
        void
        apply_commutator(VectorType &dst, const VectorType &src) const
        {
          tmp_p.reinit(src, true);
          tmp_p2.reinit(src, true);
          tmp_u.reinit(*inverse_diagonal, true);
          tmp_u2.reinit(*inverse_diagonal, true);
          discrete_brinkman->solve(tmp_p, src);
          stokes.apply_gradient(tmp_u, tmp_p);
          tmp_u.scale(*inverse_diagonal);
          velocity->vmult(tmp_u2, tmp_u);
          tmp_u2.scale(*inverse_diagonal);
          stokes.apply_divergence(tmp_p2, tmp_u2);
          // The smoothing block -C in the middle too (as the matrix-based
          // commutator): exact on modes that no free velocity sees.
          if (pressure_block != nullptr)
            {
              pressure_block->vmult(dst, tmp_p);
              tmp_p2 -= dst;
            }
          discrete_brinkman->solve(dst, tmp_p2);
          dst *= -1.;
          for (const unsigned int i : *constrained_pressure)
            dst.local_element(i) = src.local_element(i);
        }

      };
    } // namespace


    template <int dim>
    void
    PenalizedNavierStokes<dim>::setup_matrix_free_dofs()
    {
      dof_handler_velocity.distribute_dofs(fe_velocity);
      dof_handler_pressure.distribute_dofs(fe_pressure);

      // Number both like the blocks of the combined handler, so that
      // vectors, constraints and the pressure matrices carry over by index.
      const types::global_dof_index n_u = dof_handler_velocity.n_dofs();
      const IndexSet &owned_u = dof_handler_velocity.locally_owned_dofs();
      const IndexSet &owned_p = dof_handler_pressure.locally_owned_dofs();
      std::vector<types::global_dof_index> new_u(owned_u.n_elements()),
        new_p(owned_p.n_elements());
      std::vector<types::global_dof_index> combined(fe.n_dofs_per_cell()),
        velocity(fe_velocity.n_dofs_per_cell()),
        pressure(fe_pressure.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(combined);
            typename DoFHandler<dim>::active_cell_iterator(
              &triangulation,
              cell->level(),
              cell->index(),
              &dof_handler_velocity)
              ->get_dof_indices(velocity);
            typename DoFHandler<dim>::active_cell_iterator(
              &triangulation,
              cell->level(),
              cell->index(),
              &dof_handler_pressure)
              ->get_dof_indices(pressure);
            for (unsigned int k = 0; k < combined.size(); ++k)
              {
                const auto base = fe.system_to_base_index(k);
                if (base.first.first == 0)
                  {
                    const auto i =
                      velocity[fe_velocity.component_to_system_index(
                        base.first.second, base.second)];
                    if (owned_u.is_element(i))
                      new_u[owned_u.index_within_set(i)] = combined[k];
                  }
                else
                  {
                    const auto i = pressure[base.second];
                    if (owned_p.is_element(i))
                      new_p[owned_p.index_within_set(i)] = combined[k] - n_u;
                  }
              }
          }
      dof_handler_velocity.renumber_dofs(new_u);
      dof_handler_pressure.renumber_dofs(new_p);
      AssertThrow(dof_handler_velocity.locally_owned_dofs() ==
                      owned_partitioning[0] &&
                    dof_handler_pressure.locally_owned_dofs() ==
                      owned_partitioning[1],
                  ExcInternalError());
    }


    template <int dim>
    unsigned int
    PenalizedNavierStokes<dim>::solve_matrix_free(const Assembly kind,
                                                  const double   dt)
    {
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;
      Assert(kind == Assembly::steady_stokes, ExcNotImplemented());
      (void)kind;

      matrix_free_data = std::make_shared<MatrixFreeData>();
      MatrixFreeData               &data  = *matrix_free_data;
      const double                  mu    = fluid_parameters.viscosity;
      const types::global_dof_index n_u   = dof_handler_velocity.n_dofs();
      const SolverParameters::Schur schur = solver_parameters.schur;
      const bool laplace = (schur == SolverParameters::Schur::cahouet_chabard);
      const bool commutator =
        (schur == SolverParameters::Schur::least_squares_commutator);
      const bool smooth = smooth_solid_pressure();

      BlockVectorType rhs, lifting, delta;
      // Least-squares commutator: B^T and B, released once X is formed.
      TrilinosWrappers::SparseMatrix gradient, divergence;
      // The smoothing's lifting: the pressure constraints with their
      // values (pressure regions).
      AffineConstraints<double> pressure_lifting_constraints;
      {
        TimerOutput::Scope t(timer, "fluid: assemble");

        // Homogeneous copies of the combined constraints, split by block
        // (and the pressure ones with their values for the smoothing).
        split_block_constraints(constraints,
                                n_u,
                                relevant_partitioning[0],
                                relevant_partitioning[1],
                                data.velocity_constraints,
                                data.pressure_constraints,
                                smooth ? &pressure_lifting_constraints :
                                         nullptr);

        typename MatrixFree<dim, double>::AdditionalData additional_data;
        additional_data.tasks_parallel_scheme =
          MatrixFree<dim, double>::AdditionalData::none;
        additional_data.mapping_update_flags =
          update_gradients | update_JxW_values;
        data.matrix_free = std::make_shared<MatrixFree<dim, double>>();
        data.matrix_free->reinit(
          data.mapping,
          std::vector<const DoFHandler<dim> *>{&dof_handler_velocity,
                                               &dof_handler_pressure},
          std::vector<const AffineConstraints<double> *>{
            &data.velocity_constraints, &data.pressure_constraints},
          QGauss<1>(fe.degree + 1),
          additional_data);
        const MatrixFree<dim, double> &matrix_free = *data.matrix_free;

        data.coefficients =
          std::make_shared<VelocityCoefficients<dim, double>>();
        data.coefficients->viscosity = mu;
        data.velocity_operator =
          std::make_shared<VelocityOperator<dim, 2, double>>();
        data.velocity_operator->reinit(
          data.matrix_free, data.coefficients, data.velocity_constraints, 0, 0);
        data.stokes.reinit(data.matrix_free,
                           data.velocity_operator,
                           data.velocity_constraints,
                           data.pressure_constraints,
                           smooth ? &data.pressure_block : nullptr);
        data.stokes.initialize_dof_vector(rhs);
        data.stokes.initialize_dof_vector(lifting);
        data.stokes.initialize_dof_vector(delta);

        // Pressure blocks of the Schur approximation (Q1, small), or B^T
        // and B whose product gives X (released once X is formed).
        data.pressure_mass.clear();
        data.pressure_laplace.clear();
        data.discrete_brinkman_inverse.clear();
        data.discrete_brinkman.clear();
        data.pressure_block.clear();
        // A Q1 pressure matrix with the pressure constraints' pattern.
        const auto reinit_pressure_matrix =
          [&](TrilinosWrappers::SparseMatrix &matrix) {
            TrilinosWrappers::SparsityPattern sparsity(owned_partitioning[1],
                                                       owned_partitioning[1],
                                                       relevant_partitioning[1],
                                                       mpi_communicator);
            DoFTools::make_sparsity_pattern(dof_handler_pressure,
                                            sparsity,
                                            data.pressure_constraints,
                                            false);
            sparsity.compress();
            matrix.reinit(sparsity);
          };
        if (smooth)
          reinit_pressure_matrix(data.pressure_block);
        if (commutator)
          {
            // Rows written by other ranks reach their owners in compress()
            // (a rectangular Trilinos pattern with writable rows corrupted
            // the heap on 2 ranks).
            DynamicSparsityPattern sparsity(dof_handler_velocity.n_dofs(),
                                            dof_handler_pressure.n_dofs(),
                                            relevant_partitioning[0]),
              transposed(dof_handler_pressure.n_dofs(),
                         dof_handler_velocity.n_dofs(),
                         relevant_partitioning[1]);
            std::vector<types::global_dof_index> u(fe_velocity.n_dofs_per_cell()),
              p(fe_pressure.n_dofs_per_cell());
            for (const auto &cell : dof_handler_velocity.active_cell_iterators())
              if (cell->is_locally_owned())
                {
                  cell->get_dof_indices(u);
                  typename DoFHandler<dim>::active_cell_iterator(
                    &triangulation,
                    cell->level(),
                    cell->index(),
                    &dof_handler_pressure)
                    ->get_dof_indices(p);
                  data.velocity_constraints.add_entries_local_to_global(
                    u, data.pressure_constraints, p, sparsity, false);
                  data.pressure_constraints.add_entries_local_to_global(
                    p, data.velocity_constraints, u, transposed, false);
                }
            SparsityTools::distribute_sparsity_pattern(sparsity,
                                                       owned_partitioning[0],
                                                       mpi_communicator,
                                                       relevant_partitioning[0]);
            gradient.reinit(owned_partitioning[0],
                            owned_partitioning[1],
                            sparsity,
                            mpi_communicator);
            SparsityTools::distribute_sparsity_pattern(transposed,
                                                       owned_partitioning[1],
                                                       mpi_communicator,
                                                       relevant_partitioning[1]);
            divergence.reinit(owned_partitioning[1],
                              owned_partitioning[0],
                              transposed,
                              mpi_communicator);
          }
        else
          {
            reinit_pressure_matrix(data.pressure_mass);
            reinit_pressure_matrix(data.pressure_laplace);
          }

        // The same coefficients as assemble(): beta, the right-hand side
        // f + beta u_s, and the Schur weights.
        const double beta_floor = viscous_beta_floor();

        const QGauss<dim>                quadrature(fe.degree + 1);
        const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
        const unsigned int               n_q = quadrature.size();
        FEValues<dim>                    pressure_values(data.mapping,
                                      fe_pressure,
                                      quadrature,
                                      update_values | update_gradients |
                                        update_quadrature_points |
                                        update_JxW_values);
        FEValues<dim>                    velocity_values(data.mapping,
                                      fe_velocity,
                                      quadrature,
                                      update_gradients);
        FEFaceValues<dim>                velocity_face_values(data.mapping,
                                               fe_velocity,
                                               face_quadrature,
                                               update_values |
                                                 update_normal_vectors |
                                                 update_JxW_values);
        FEFaceValues<dim>                pressure_face_values(data.mapping,
                                               fe_pressure,
                                               face_quadrature,
                                               update_values |
                                                 update_JxW_values);
        const FEValuesExtractors::Vector velocities(0);
        const unsigned int n_p_dofs = fe_pressure.n_dofs_per_cell();
        const unsigned int n_u_dofs = fe_velocity.n_dofs_per_cell();
        FullMatrix<double> local_mass(n_p_dofs, n_p_dofs),
          local_laplace(n_p_dofs, n_p_dofs), local_gradient(n_u_dofs, n_p_dofs),
          local_smoothing(n_p_dofs, n_p_dofs),
          local_divergence(n_p_dofs, n_u_dofs);
        Vector<double> local_pressure_rhs(n_p_dofs);
        Vector<double>                       local_face_rhs(n_u_dofs);
        std::vector<types::global_dof_index> u_dofs(n_u_dofs), p_dofs(n_p_dofs);
        std::vector<double>                  void_fraction(n_q, 1.);
        std::vector<Tensor<1, dim>>          solid_velocity(n_q);
        std::vector<int>                     solid_index(n_q, -1);
        Vector<double>                       force_value(dim);

        const unsigned int n_batches = matrix_free.n_cell_batches();
        data.coefficients->reaction.reinit(n_batches, n_q);
        if (boundary_conditions.has_pressure_regions())
          data.coefficients->viscosity_scale.resize(
            n_batches, VectorizedArray<double>(1.));
        typename VelocityOperator<dim, 2, double>::Evaluation  phi(matrix_free,
                                                                  0,
                                                                  0);
        AlignedVector<Tensor<1, dim, VectorizedArray<double>>> rhs_values(n_q);
        for (unsigned int batch = 0; batch < n_batches; ++batch)
          {
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                const auto cell_u =
                  matrix_free.get_cell_iterator(batch, lane, 0);
                const auto cell_p =
                  matrix_free.get_cell_iterator(batch, lane, 1);
                pressure_values.reinit(cell_p);
                const auto &points = pressure_values.get_quadrature_points();
                if (solid_field != nullptr && !rigid_nodes())
                  evaluate_solids(*cell_p,
                                        points,
                                        void_fraction,
                                        solid_velocity,
                                        solid_index);
                // The hybrid model's porous cells: Darcy's drag (Stokes:
                // no Forchheimer term).
                const PorousCell<dim> porous = porous_cell(*cell_p);
                cell_u->get_dof_indices(u_dofs);
                cell_p->get_dof_indices(p_dofs);

                // As assemble(): with rigid nodes the Schur mass is scaled by
                // the cell's free velocity fraction, and the pressure is
                // smoothed where few velocity nodes are free.
                const double h = cell_p->diameter() / std::sqrt(double(dim));
                double       free_fraction = 1, solid_smoothing = 0;
                if (!rigid_dof_grain.empty())
                  {
                    unsigned int n_rigid = 0, n_fixed = 0;
                    for (const auto i : u_dofs)
                      {
                        n_rigid += rigid_dof_grain.count(i);
                        if (smooth)
                          n_fixed += is_fixed_velocity(i);
                      }
                    std::tie(free_fraction, solid_smoothing) =
                      rigid_cell_weights(n_u_dofs, n_rigid, n_fixed, h);
                  }
                if (solid_smoothing > 0)
                  {
                    local_smoothing    = 0;
                    local_pressure_rhs = 0;
                    for (unsigned int q = 0; q < n_q; ++q)
                      for (unsigned int i = 0; i < n_p_dofs; ++i)
                        for (unsigned int j = 0; j < n_p_dofs; ++j)
                          local_smoothing(i, j) -=
                            solid_smoothing *
                            (pressure_values.shape_grad(i, q) *
                             pressure_values.shape_grad(j, q)) *
                            pressure_values.JxW(q);
                    pressure_lifting_constraints.distribute_local_to_global(
                      local_smoothing,
                      local_pressure_rhs,
                      p_dofs,
                      data.pressure_block,
                      rhs.block(1),
                      true);
                  }
                // A pressure region (reservoir) carries only -(p, div v), as
                // in assemble().
                const bool reservoir =
                  boundary_conditions.has_pressure_regions() &&
                  boundary_conditions.pressure_region(cell_p->center()) !=
                    nullptr;
                if (reservoir)
                  data.coefficients->viscosity_scale[batch][lane] = 0.;

                if (commutator)
                  {
                    // B^T: -(p, div v).
                    velocity_values.reinit(cell_u);
                    local_gradient = 0;
                    for (unsigned int q = 0; q < n_q; ++q)
                      {
                        const double JxW = pressure_values.JxW(q);
                        for (unsigned int i = 0; i < n_u_dofs; ++i)
                          {
                            const double div =
                              velocity_values[velocities].divergence(i, q) *
                              JxW;
                            for (unsigned int j = 0; j < n_p_dofs; ++j)
                              local_gradient(i, j) -=
                                div * pressure_values.shape_value(j, q);
                          }
                      }
                    data.velocity_constraints.distribute_local_to_global(
                      local_gradient,
                      u_dofs,
                      data.pressure_constraints,
                      p_dofs,
                      gradient);
                    local_divergence.copy_transposed(local_gradient);
                    data.pressure_constraints.distribute_local_to_global(
                      local_divergence,
                      p_dofs,
                      data.velocity_constraints,
                      u_dofs,
                      divergence);
                  }

                local_mass    = 0;
                local_laplace = 0;
                for (unsigned int q = 0; q < n_q; ++q)
                  {
                    const double drag =
                      porous.porous && !reservoir ?
                        mu * porous.inverse_permeability :
                        0.;
                    const double beta =
                      reservoir ? 0. :
                                  brinkman_coefficient(void_fraction[q], dt) +
                                    drag;
                    data.coefficients->reaction(batch, q)[lane] = beta;
                    if (reservoir)
                      force_value = 0;
                    else
                      body_force->vector_value(points[q], force_value);
                    for (unsigned int d = 0; d < dim; ++d)
                      rhs_values[q][d][lane] =
                        force_value[d] +
                        (beta - drag) * solid_velocity[q][d] +
                        drag * porous.grain_flux()[d];

                    double mass_weight = free_fraction / mu;
                    if (schur == SolverParameters::Schur::weighted_mass)
                      mass_weight = free_fraction / (mu + beta * h * h);
                    const double laplace_weight =
                      laplace ? 1. / (beta + beta_floor) : 0.;
                    const double JxW = pressure_values.JxW(q);
                    for (unsigned int i = 0; i < n_p_dofs; ++i)
                      for (unsigned int j = 0; j < n_p_dofs; ++j)
                        {
                          local_mass(i, j) +=
                            mass_weight * pressure_values.shape_value(i, q) *
                            pressure_values.shape_value(j, q) * JxW;
                          local_laplace(i, j) +=
                            laplace_weight *
                            (pressure_values.shape_grad(i, q) *
                             pressure_values.shape_grad(j, q)) *
                            JxW;
                        }
                  }

                // Pressure faces: do-nothing condition mu du/dn - p n = -p_b n,
                // and weak p = 0 in the Schur Laplacian.
                for (const unsigned int f : cell_u->face_indices())
                  if (cell_u->face(f)->at_boundary() &&
                      boundary_conditions.face(cell_u->face(f)->boundary_id())
                          .type == BoundaryConditions<dim>::Type::pressure)
                    {
                      const double p_b =
                        boundary_conditions.face(cell_u->face(f)->boundary_id())
                          .pressure;
                      velocity_face_values.reinit(cell_u, f);
                      local_face_rhs = 0;
                      for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                        for (unsigned int i = 0; i < n_u_dofs; ++i)
                          local_face_rhs(i) -=
                            p_b *
                            (velocity_face_values[velocities].value(i, q) *
                             velocity_face_values.normal_vector(q)) *
                            velocity_face_values.JxW(q);
                      data.velocity_constraints.distribute_local_to_global(
                        local_face_rhs, u_dofs, rhs.block(0));
                      if (laplace)
                        {
                          pressure_face_values.reinit(cell_p, f);
                          const double penalty = 1. / (beta_floor * h);
                          for (unsigned int q = 0; q < face_quadrature.size();
                               ++q)
                            for (unsigned int i = 0; i < n_p_dofs; ++i)
                              for (unsigned int j = 0; j < n_p_dofs; ++j)
                                local_laplace(i, j) +=
                                  penalty *
                                  pressure_face_values.shape_value(i, q) *
                                  pressure_face_values.shape_value(j, q) *
                                  pressure_face_values.JxW(q);
                        }
                    }
                if (!commutator)
                  data.pressure_constraints.distribute_local_to_global(
                    local_mass, p_dofs, data.pressure_mass);
                if (laplace)
                  data.pressure_constraints.distribute_local_to_global(
                    local_laplace, p_dofs, data.pressure_laplace);
              }
            phi.reinit(batch);
            for (unsigned int q = 0; q < n_q; ++q)
              phi.submit_value(rhs_values[q], q);
            phi.integrate_scatter(EvaluationFlags::values, rhs.block(0));
          }
        rhs.compress(VectorOperation::add);
        if (smooth)
          data.pressure_block.compress(VectorOperation::add);
        if (commutator)
          {
            gradient.compress(VectorOperation::add);
            divergence.compress(VectorOperation::add);
          }
        else
          {
            data.pressure_mass.compress(VectorOperation::add);
            data.pressure_laplace.compress(VectorOperation::add);
          }

        // Inhomogeneous constraints (inflow, grain velocities, pressure
        // regions): solve for the correction to the lifting that carries
        // their values.
        for (const auto &line : constraints.get_lines())
          if (line.inhomogeneity != 0)
            {
              const unsigned int b = line.index < n_u ? 0 : 1;
              const auto         i = line.index - (b == 0 ? 0 : n_u);
              if (lifting.block(b).in_local_range(i))
                lifting.block(b)(i) = line.inhomogeneity;
            }
        data.stokes.subtract_plain(rhs, lifting);

        if (!boundary_conditions.has_pressure_face())
          {
            // As solve_linear(): project the continuity rows onto the range.
            const auto rows =
              constrained_local_rows(*matrix_free.get_vector_partitioner(1),
                                     data.pressure_constraints);
            std::vector<bool> constrained(rhs.block(1).locally_owned_size());
            for (const auto i : rows)
              constrained[i] = true;
            double       sum   = 0;
            unsigned int count = 0;
            for (unsigned int i = 0; i < constrained.size(); ++i)
              if (!constrained[i])
                {
                  sum += rhs.block(1).local_element(i);
                  ++count;
                }
            sum   = Utilities::MPI::sum(sum, mpi_communicator);
            count = Utilities::MPI::sum(count, mpi_communicator);
            for (unsigned int i = 0; i < constrained.size(); ++i)
              if (!constrained[i])
                rhs.block(1).local_element(i) -= sum / count;
          }
      }

      {
        TimerOutput::Scope t(timer, "fluid: preconditioner setup");
        const double inflation = rigid_nodes() ? rigid_node_inflation() : 0.;
        const auto   level_constraints =
          [this, inflation](const DoFHandler<dim>     &dof,
                            AffineConstraints<double> &c) {
            DoFTools::make_hanging_node_constraints(dof, c);
            for (unsigned int b = 0; b < boundary_conditions.n_boundary_ids(); ++b)
              {
                const auto type = boundary_conditions.face(b).type;
                if (type == BoundaryConditions<dim>::Type::pressure)
                  continue;
                std::vector<bool> mask(dim, true);
                if (type == BoundaryConditions<dim>::Type::symmetry)
                  for (unsigned int d = 0; d < dim; ++d)
                    mask[d] = (d == b / 2);
                DoFTools::make_zero_boundary_constraints(dof,
                                                         b,
                                                         c,
                                                         ComponentMask(mask));
              }
            if (rigid_nodes() || constrained_interiors())
              add_solid_constraints(dof, c, inflation, nullptr);
          };
        // Every level sees the grains as the fine operator does
        // (rediscretization with the scene's void fraction), so a coarse
        // cell cut by a grain is penalized as a whole: the coarse obstacle
        // contains the fine one. Measured worse: the exact indicator at the
        // coarse quadrature points (a coarse obstacle inside the fine one;
        // 160-180 FGMRES iterations at Theta = 1e12) and a penalty capped at
        // 1e2..1e4 mu / h^2 on coarse levels (no convergence at N = 16).
        const auto level_coefficient =
          [this, dt, mu](const CellAccessor<dim, dim>  &cell,
                     const std::vector<Point<dim>> &points,
                     const bool,
                     std::vector<double> &beta) {
            beta.assign(points.size(), 0.);
            if (const PorousCell<dim> porous = porous_cell(cell); porous.porous)
              beta.assign(points.size(), mu * porous.inverse_permeability);
            if (solid_field == nullptr || rigid_nodes())
              return;
            std::vector<double>         vf;
            std::vector<Tensor<1, dim>> u_s;
            std::vector<int>            index;
            evaluate_solids(cell, points, vf, u_s, index);
            for (unsigned int q = 0; q < points.size(); ++q)
              beta[q] += brinkman_coefficient(vf[q], dt);
          };
        typename VelocityMultigrid<dim>::Settings settings;
        settings.smoother_degree = solver_parameters.smoother_degree;
        settings.smoothing_range = solver_parameters.smoothing_range;
        settings.geometric_levels = solver_parameters.multigrid_geometric_levels;
        settings.coarse_tolerance = solver_parameters.multigrid_coarse_tolerance;
        data.multigrid.initialize(dof_handler_velocity,
                                  data.velocity_constraints,
                                  data.velocity_operator,
                                  level_constraints,
                                  level_coefficient,
                                  mu,
                                  settings);

        if (commutator)
          {
            // X = B D^-1 B^T + C, D = diag(A) of the matrix-free operator.
            data.velocity_operator->compute_inverse_diagonal(
              data.inverse_diagonal);
            TrilinosWrappers::MPI::Vector inverse(owned_partitioning[0],
                                                  mpi_communicator);
            for (const auto i : owned_partitioning[0])
              inverse(i) = data.inverse_diagonal(i);
            inverse.compress(VectorOperation::insert);
            // B and B^T both assembled: deal.II's Tmmult (B^T alone)
            // corrupted the heap on 2 ranks.
            TrilinosWrappers::SparseMatrix product;
            divergence.mmult(product, gradient, inverse);
            gradient.clear();
            divergence.clear();
            discrete_brinkman_from_product(product,
                                           smooth ? &data.pressure_block :
                                                    nullptr,
                                           data.discrete_brinkman);
            data.discrete_brinkman_inverse.initialize(
              data.discrete_brinkman,
              schur_inner_solver(),
              solver_parameters.schur_inner_tolerance);
          }
        else
          data.pressure_mass_ilu.initialize(data.pressure_mass);
        if (laplace)
          {
            data.pressure_laplace_amg.initialize(data.pressure_laplace,
                                                 pressure_laplace_amg_data());
          }
      }

      TimerOutput::Scope t(timer, "fluid: solve");
      // Start from the previous state (cheap re-solves), correction form.
      {
        BlockVector owned(owned_partitioning, mpi_communicator);
        owned = solution;
        for (unsigned int b = 0; b < 2; ++b)
          std::copy(owned.block(b).begin(),
                    owned.block(b).end(),
                    delta.block(b).begin());
        for (const auto &line : constraints.get_lines())
          {
            const unsigned int b = line.index < n_u ? 0 : 1;
            const auto         i = line.index - (b == 0 ? 0 : n_u);
            if (delta.block(b).in_local_range(i))
              delta.block(b)(i) = 0;
          }
      }

      const double  rhs_norm = rhs.l2_norm();
      SolverControl control(
        solver_parameters.max_linear_iterations,
        std::max(solver_parameters.linear_tolerance * rhs_norm, 1e-300),
        false,
        false);
      const std::vector<unsigned int> constrained_pressure =
        constrained_local_rows(*data.matrix_free->get_vector_partitioner(1),
                               data.pressure_constraints);
      const MatrixFreeBlockPreconditioner<dim> preconditioner =
        commutator ?
          MatrixFreeBlockPreconditioner<dim>(
            data.stokes,
            data.multigrid,
            *data.velocity_operator,
            data.discrete_brinkman_inverse,
            data.inverse_diagonal,
            smooth ? &data.pressure_block : nullptr,
            constrained_pressure) :
          MatrixFreeBlockPreconditioner<dim>(
            data.stokes,
            data.multigrid,
            data.pressure_mass_ilu,
            laplace ? &data.pressure_laplace_amg : nullptr);
      SolverFGMRES<BlockVectorType> solver(
        control, typename SolverFGMRES<BlockVectorType>::AdditionalData(
          solver_parameters.krylov_restart));
      try
        {
          if (rhs_norm > 0)
            solver.solve(data.stokes, delta, rhs, preconditioner);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          AssertThrow(false,
                      ExcMessage(linear_solver_failure(e, control.tolerance())));
        }

      BlockVector x(owned_partitioning, mpi_communicator);
      for (unsigned int b = 0; b < 2; ++b)
        std::copy(delta.block(b).begin(),
                  delta.block(b).end(),
                  x.block(b).begin());
      // Everything above is rebuilt by the next solve: release it before
      // the reactions and the grains' step, so that the peak memory is the
      // larger of the two phases rather than their sum.
      const unsigned int iterations = rhs_norm > 0 ? control.last_step() : 0;
      const DiscreteBrinkmanSolver &inner = data.discrete_brinkman_inverse;
      if (inner.solves > 0)
        pcout << "      commutator: " << inner.solves << " inner solves on X"
              << (inner.is_exact() ?
                    " (direct)" :
                    ", CG iterations each on average: " +
                      std::to_string(inner.iterations / inner.solves))
              << ", " << inner.wall_time << " s" << std::endl;
      matrix_free_data.reset();
      rhs.reinit(0);
      lifting.reinit(0);
      delta.reinit(0);
      GrowingVectorMemory<BlockVectorType>::release_unused_memory();
      GrowingVectorMemory<VectorType>::release_unused_memory();
      // A zero right-hand side (fluid and grains at rest) needs no solve:
      // zero iterations, not the solver control's unset step count.
      return accept_linear_solution(x, iterations);
    }

    template void
    PenalizedNavierStokes<2>::setup_matrix_free_dofs();
    template void
    PenalizedNavierStokes<3>::setup_matrix_free_dofs();
    template unsigned int
    PenalizedNavierStokes<2>::solve_matrix_free(const Assembly, const double);
    template unsigned int
    PenalizedNavierStokes<3>::solve_matrix_free(const Assembly, const double);
  } // namespace fluid
} // namespace softsand
