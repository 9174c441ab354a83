// The transient matrix-free step's per-mesh set-up: MatrixFree on the
// mesh's own constraints (hanging nodes, walls, pressure regions), B^T and
// B from the cells' local tensors, the traction faces, the pressure faces'
// right-hand side and the body force.

#include <deal.II/base/quadrature_lib.h>


#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/vector_memory.h>

#include <deal.II/matrix_free/fe_evaluation.h>

#include <softsand/base/warnings.h>
#include <softsand/fluid/box_cell_tensors.h>
#include <softsand/fluid/pressure_region.h>
#include <softsand/fluid/transient_matrix_free.h>

#include <EpetraExt_Transpose_RowMatrix.h>

namespace softsand
{
  namespace fluid
  {
    using namespace internal;

    template <int dim>
    void
    PenalizedNavierStokes<dim>::setup_transient_matrix_free()
    {
      TimerOutput::Scope t(timer, "fluid: setup dofs");
      transient_matrix_free = std::make_shared<TransientMatrixFree>();
      TransientMatrixFree          &data = *transient_matrix_free;
      const types::global_dof_index n_u  = dof_handler_velocity.n_dofs();

      // The mesh's constraints: those of make_constraints() without grains.
      AffineConstraints<double> mesh;
      {
        const IndexSet relevant =
          DoFTools::extract_locally_relevant_dofs(dof_handler);
        mesh.reinit(relevant);
        DoFTools::make_hanging_node_constraints(dof_handler, mesh);
        boundary_conditions.make_velocity_constraints(dof_handler, mesh, time);
        make_pressure_region_constraints(dof_handler,
                                         boundary_conditions.inlet_region(),
                                         boundary_conditions.perimeter_region(),
                                         mesh);
        mesh.close();
      }
      split_block_constraints(mesh,
                              n_u,
                              relevant_partitioning[0],
                              relevant_partitioning[1],
                              data.velocity_constraints,
                              data.pressure_constraints,
                              &data.pressure_values);

      typename MatrixFree<dim, double>::AdditionalData additional_data;
      additional_data.tasks_parallel_scheme =
        MatrixFree<dim, double>::AdditionalData::none;
      additional_data.mapping_update_flags =
        update_gradients | update_JxW_values | update_quadrature_points;
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
      data.coefficients = std::make_shared<VelocityCoefficients<dim, double>>();
      data.coefficients->viscosity = fluid_parameters.viscosity;
      data.velocity_operator =
        std::make_shared<VelocityOperator<dim, 2, double>>();

      // The lexicographic numbering of the kernels against the cell's DoF
      // indices, checked once per mesh: the residual of the reactions maps
      // kernel rows to DoFs with it.
      const unsigned int n_batches = matrix_free.n_cell_batches();
      const std::vector<unsigned int> h2l =
        FETools::hierarchic_to_lexicographic_numbering<dim>(2);
      if (n_batches > 0)
        {
          LinearAlgebra::distributed::Vector<double> index;
          matrix_free.initialize_dof_vector(index, 0);
          for (unsigned int i = 0; i < index.locally_owned_size(); ++i)
            index.local_element(i) =
              index.get_partitioner()->local_to_global(i);
          index.update_ghost_values();
          typename VelocityOperator<dim, 2, double>::Evaluation phi(matrix_free,
                                                                    0,
                                                                    0);
          phi.reinit(0);
          phi.read_dof_values_plain(index);
          std::vector<types::global_dof_index> dofs(
            fe_velocity.n_dofs_per_cell());
          matrix_free.get_cell_iterator(0, 0, 0)->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              const auto [c, b] = fe_velocity.system_to_component_index(i);
              AssertThrow(std::abs(phi.begin_dof_values()[c * h2l.size() +
                                                          h2l[b]][0] -
                                   double(dofs[i])) < 0.5,
                          ExcInternalError());
            }
        }

      data.reservoir.assign(n_batches, 0);
      for (unsigned int batch = 0; batch < n_batches; ++batch)
        data.reservoir[batch] =
          boundary_conditions.has_pressure_regions() &&
          boundary_conditions.pressure_region(
            matrix_free.get_cell_iterator(batch, 0, 0)->center()) != nullptr;

      // Traction faces: pressure faces and the surfaces of pressure regions,
      // seen from the fluid's cells (assemble()).
      data.traction_faces.clear();
      for (unsigned int batch = 0; batch < n_batches; ++batch)
        for (unsigned int lane = 0;
             lane < matrix_free.n_active_entries_per_cell_batch(batch);
             ++lane)
          {
            const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
            if (boundary_conditions.has_pressure_regions() &&
                boundary_conditions.pressure_region(cell->center()) != nullptr)
              continue;
            for (const unsigned int f : cell->face_indices())
              {
                const auto face = cell->face(f);
                if (face->at_boundary())
                  {
                    if (boundary_conditions.face(face->boundary_id()).type ==
                        BoundaryConditions<dim>::Type::pressure)
                      data.traction_faces.push_back(
                        {{int(batch), int(lane), int(f), -1}});
                  }
                else if (boundary_conditions.has_pressure_regions())
                  {
                    if (face->has_children())
                      {
                        for (unsigned int sf = 0; sf < face->n_children(); ++sf)
                          if (boundary_conditions.pressure_region(
                                cell->neighbor_child_on_subface(f, sf)
                                  ->center()) != nullptr)
                            data.traction_faces.push_back(
                              {{int(batch), int(lane), int(f), int(sf)}});
                      }
                    else if (boundary_conditions.pressure_region(
                               cell->neighbor(f)->center()) != nullptr)
                      data.traction_faces.push_back(
                        {{int(batch), int(lane), int(f), -1}});
                  }
              }
          }
      data.has_traction =
        Utilities::MPI::max(data.traction_faces.empty() ? 0u : 1u,
                            mpi_communicator) > 0;
      if (data.has_traction)
        {
          DynamicSparsityPattern dsp(relevant_partitioning[0]);
          std::vector<types::global_dof_index> dofs(
            fe_velocity.n_dofs_per_cell());
          for (const auto &[batch, lane, f, sf] : data.traction_faces)
            {
              (void)f;
              (void)sf;
              matrix_free.get_cell_iterator(batch, lane, 0)->get_dof_indices(
                dofs);
              data.velocity_constraints.add_entries_local_to_global(dofs,
                                                                    dsp,
                                                                    false);
            }
          SparsityTools::distribute_sparsity_pattern(dsp,
                                                     owned_partitioning[0],
                                                     mpi_communicator,
                                                     relevant_partitioning[0]);
          data.traction.reinit(owned_partitioning[0],
                               owned_partitioning[0],
                               dsp,
                               mpi_communicator);
        }

      // The Q1 pattern of the rigid-node smoothing.
      data.has_smoothing = smooth_solid_pressure();
      if (data.has_smoothing)
      {
        DynamicSparsityPattern dsp(relevant_partitioning[1]);
        DoFTools::make_sparsity_pattern(dof_handler_pressure,
                                        dsp,
                                        data.pressure_constraints,
                                        false);
        SparsityTools::distribute_sparsity_pattern(dsp,
                                                   owned_partitioning[1],
                                                   mpi_communicator,
                                                   relevant_partitioning[1]);
        data.smoothing.reinit(owned_partitioning[1],
                              owned_partitioning[1],
                              dsp,
                              mpi_communicator);
      }

      // Pressure faces: the do-nothing condition's -p_b (v . n).
      matrix_free.initialize_dof_vector(data.face_rhs, 0);
      {
        const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
        FEFaceValues<dim>                face_values(data.mapping,
                                      fe_velocity,
                                      face_quadrature,
                                      update_values | update_normal_vectors |
                                        update_JxW_values);
        Vector<double> local(fe_velocity.n_dofs_per_cell());
        std::vector<types::global_dof_index> dofs(
          fe_velocity.n_dofs_per_cell());
        for (const auto &cell : dof_handler_velocity.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  boundary_conditions.face(cell->face(f)->boundary_id()).type ==
                    BoundaryConditions<dim>::Type::pressure)
                {
                  const double p_b =
                    boundary_conditions.face(cell->face(f)->boundary_id())
                      .pressure;
                  face_values.reinit(cell, f);
                  local = 0;
                  add_pressure_face_term(face_values, p_b, local);
                  cell->get_dof_indices(dofs);
                  data.velocity_constraints.distribute_local_to_global(
                    local, dofs, data.face_rhs);
                }
        data.face_rhs.compress(VectorOperation::add);
      }

      // B^T and B for the pressure matrix X = B D^-1 B^T of each step.
        {
          DynamicSparsityPattern sparsity(dof_handler_velocity.n_dofs(),
                                          dof_handler_pressure.n_dofs(),
                                          relevant_partitioning[0]);
          std::vector<types::global_dof_index> u(fe_velocity.n_dofs_per_cell()),
            p(fe_pressure.n_dofs_per_cell());
          for (unsigned int batch = 0; batch < n_batches; ++batch)
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                matrix_free.get_cell_iterator(batch, lane, 0)
                  ->get_dof_indices(u);
                matrix_free.get_cell_iterator(batch, lane, 1)
                  ->get_dof_indices(p);
                data.velocity_constraints.add_entries_local_to_global(
                  u, data.pressure_constraints, p, sparsity, false);
              }
          SparsityTools::distribute_sparsity_pattern(sparsity,
                                                     owned_partitioning[0],
                                                     mpi_communicator,
                                                     relevant_partitioning[0]);
          data.gradient.reinit(owned_partitioning[0],
                               owned_partitioning[1],
                               sparsity,
                               mpi_communicator);
          LocalTensors<dim>        tensors;
          LocalTensorComputer<dim> computer;
          FullMatrix<double> local_gradient(u.size(), p.size());
          for (unsigned int batch = 0; batch < n_batches; ++batch)
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
                cell->get_dof_indices(u);
                matrix_free.get_cell_iterator(batch, lane, 1)
                  ->get_dof_indices(p);
                computer.compute(cell, tensors);
                for (unsigned int i = 0; i < u.size(); ++i)
                  {
                    const auto [c, b] = fe_velocity.system_to_component_index(i);
                    for (unsigned int a = 0; a < p.size(); ++a)
                      local_gradient(i, a) =
                        -tensors.coupling[c * p.size() + a][h2l[b]];
                  }
                data.velocity_constraints.distribute_local_to_global(
                  local_gradient,
                  u,
                  data.pressure_constraints,
                  p,
                  data.gradient);
              }
          data.gradient.compress(VectorOperation::add);
          {
            // B as B^T's transpose: assembling it too took a second pattern
            // and a second pass through the constraints (B's set-up 1.65 s
            // against 1.38 s per mesh, small Hele-Shaw scene, 4 cells).
            Epetra_Map pressure_map(
              data.gradient.trilinos_matrix().DomainMap());
            EpetraExt::RowMatrix_Transpose transposer(&pressure_map);
            data.divergence.reinit(
              dynamic_cast<Epetra_CrsMatrix &>(transposer(
                const_cast<Epetra_CrsMatrix &>(
                  data.gradient.trilinos_matrix()))));
          }
          const Epetra_CrsMatrix &gradient = data.gradient.trilinos_matrix();
          data.gradient_values.clear();
          data.gradient_values.reserve(gradient.NumMyNonzeros());
          for (int row = 0; row < gradient.NumMyRows(); ++row)
            {
              int     n_entries;
              double *values;
              int    *columns;
              gradient.ExtractMyRowView(row, n_entries, values, columns);
              data.gradient_values.insert(data.gradient_values.end(),
                                          values,
                                          values + n_entries);
            }
        }

      // A body force without x, y, z or t is evaluated once.
      data.constant_body_force =
        fluid_parameters.body_force.find_first_not_of("0123456789.eE+-*/(); ") ==
        std::string::npos;
      {
        Vector<double> value(dim);
        body_force->vector_value(Point<dim>(), value);
        for (unsigned int d = 0; d < dim; ++d)
          data.body_force_value[d] = value[d];
      }
    }


    template void
    PenalizedNavierStokes<2>::setup_transient_matrix_free();
    template void
    PenalizedNavierStokes<3>::setup_transient_matrix_free();
  } // namespace fluid
} // namespace softsand
