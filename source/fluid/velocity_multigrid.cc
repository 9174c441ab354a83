#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/matrix_free/fe_evaluation.h>

#include <softsand/fluid/velocity_multigrid.h>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    void
    VelocityMultigrid<dim>::initialize(
      const DoFHandler<dim>           &fine_dof_handler,
      const AffineConstraints<double> &fine_constraints,
      std::shared_ptr<const VelocityLevelOperator<dim, double>> fine_operator,
      const ConstraintFunction  &make_constraints,
      const CoefficientFunction &coefficient,
      const double               viscosity,
      const Settings            &settings)
    {
      // Release the previous hierarchy, users before the used.
      preconditioner.reset();
      multigrid.reset();
      mg_coarse.reset();
      transfer.reset();

      if (settings.geometric_levels)
        triangulations = MGTransferGlobalCoarseningTools::
          create_geometric_coarsening_sequence(
            fine_dof_handler.get_triangulation());
      else
        triangulations = {std::shared_ptr<const Triangulation<dim>>(
          &fine_dof_handler.get_triangulation(),
          [](const Triangulation<dim> *) {})};
      const unsigned int n_h_levels = triangulations.size();
      // Q1 on every mesh of the sequence, then Q2 on the active mesh.
      const unsigned int max_level = n_h_levels;
      fe_q1 = std::make_unique<FESystem<dim>>(FE_Q<dim>(1), dim);

      dof_handlers.resize(0, max_level);
      constraints.resize(0, max_level);
      operators.resize(0, max_level);
      transfers.resize(0, max_level);

      const QGauss<dim>    quadrature(2);
      const MappingQ1<dim> mapping;
      for (unsigned int level = 0; level < n_h_levels; ++level)
        {
          dof_handlers[level] =
            std::make_unique<DoFHandler<dim>>(*triangulations[level]);
          DoFHandler<dim> &dof = *dof_handlers[level];
          dof.distribute_dofs(*fe_q1);

          AffineConstraints<double> &c = constraints[level];
          c.reinit(DoFTools::extract_locally_relevant_dofs(dof));
          make_constraints(dof, c);
          c.close();

          typename MatrixFree<dim, double>::AdditionalData data;
          data.tasks_parallel_scheme =
            MatrixFree<dim, double>::AdditionalData::none;
          data.mapping_update_flags = update_gradients | update_JxW_values;
          auto matrix_free = std::make_shared<MatrixFree<dim, double>>();
          matrix_free->reinit(mapping, dof, c, QGauss<1>(2), data);

          // beta at the quadrature points of each cell batch.
          auto coefficients =
            std::make_shared<VelocityCoefficients<dim, double>>();
          coefficients->viscosity      = viscosity;
          const unsigned int n_batches = matrix_free->n_cell_batches();
          coefficients->reaction.reinit(n_batches, quadrature.size());
          FEValues<dim>       fe_values(mapping,
                                  *fe_q1,
                                  quadrature,
                                  update_quadrature_points);
          std::vector<double> beta(quadrature.size());
          for (unsigned int batch = 0; batch < n_batches; ++batch)
            for (unsigned int lane = 0;
                 lane < matrix_free->n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                const auto cell = matrix_free->get_cell_iterator(batch, lane);
                fe_values.reinit(cell);
                coefficient(*cell,
                            fe_values.get_quadrature_points(),
                            level + 1 == n_h_levels,
                            beta);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  coefficients->reaction(batch, q)[lane] = beta[q];
              }

          auto op = std::make_shared<VelocityOperator<dim, 1, double>>();
          op->reinit(matrix_free, coefficients, c, 0, 0);
          operators[level] = op;
        }
      operators[max_level] = fine_operator;

      for (unsigned int level = 0; level < max_level; ++level)
        transfers[level + 1].reinit(
          level + 1 == max_level ? fine_dof_handler : *dof_handlers[level + 1],
          *dof_handlers[level],
          level + 1 == max_level ? fine_constraints : constraints[level + 1],
          constraints[level]);
      transfer = std::make_unique<MGTransferGlobalCoarsening<dim, VectorType>>(
        transfers, [&](const unsigned int level, VectorType &vector) {
          operators[level]->initialize_dof_vector(vector);
        });

      // Chebyshev smoothing around point Jacobi.
      MGLevelObject<typename Smoother::AdditionalData> smoother_data(0,
                                                                     max_level);
      for (unsigned int level = 0; level <= max_level; ++level)
        {
          smoother_data[level].preconditioner =
            std::make_shared<DiagonalMatrix<VectorType>>();
          operators[level]->compute_inverse_diagonal(
            smoother_data[level].preconditioner->get_vector());
          smoother_data[level].smoothing_range = settings.smoothing_range;
          smoother_data[level].degree          = settings.smoother_degree;
          smoother_data[level].eig_cg_n_iterations =
            settings.eigenvalue_iterations;
        }
      mg_smoother.initialize(operators, smoother_data);
      mg_matrix.initialize(operators);

      // Coarsest mesh: CG with AMG to a modest reduction.
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        amg_data.elliptic              = true;
        amg_data.higher_order_elements = false;
        amg_data.smoother_sweeps       = 2;
        amg_data.aggregation_threshold = 0.02;
        DoFTools::extract_constant_modes(*dof_handlers[0],
                                         ComponentMask(dim, true),
                                         amg_data.constant_modes);
        coarse_amg.initialize(operators[0]->get_system_matrix(), amg_data);
      }
      mg_coarse = std::make_unique<CoarseSolver>(*operators[0],
                                                 coarse_amg,
                                                 settings.coarse_tolerance);

      multigrid      = std::make_unique<Multigrid<VectorType>>(mg_matrix,
                                                          *mg_coarse,
                                                          *transfer,
                                                          mg_smoother,
                                                          mg_smoother,
                                                          0,
                                                          max_level);
      preconditioner = std::make_unique<
        PreconditionMG<dim,
                       VectorType,
                       MGTransferGlobalCoarsening<dim, VectorType>>>(
        fine_dof_handler, *multigrid, *transfer);
    }


    template <int dim>
    void
    VelocityMultigrid<dim>::vmult(VectorType &dst, const VectorType &src) const
    {
      preconditioner->vmult(dst, src);
    }


    template <int dim>
    void
    VelocityMultigrid<dim>::CoarseSolver::operator()(
      const unsigned int,
      VectorType       &dst,
      const VectorType &src) const
    {
      ReductionControl     control(100, 1e-300, tolerance, false, false);
      SolverCG<VectorType> cg(control);
      dst = 0;
      try
        {
          cg.solve(matrix, dst, src, amg);
        }
      catch (const SolverControl::NoConvergence &)
        {}
      ++n_calls;
      n_iterations += control.last_step();
    }


    template <int dim>
    std::vector<types::global_dof_index>
    VelocityMultigrid<dim>::level_sizes() const
    {
      std::vector<types::global_dof_index> sizes;
      for (unsigned int level = 0; level <= operators.max_level(); ++level)
        sizes.push_back(operators[level]->m());
      return sizes;
    }

    template class VelocityMultigrid<2>;
    template class VelocityMultigrid<3>;
  } // namespace fluid
} // namespace softsand
