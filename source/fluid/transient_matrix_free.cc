// The transient matrix-free step of PenalizedNavierStokes (fluid solver/
// transient solver = matrix free): the BDF step of the penalized
// Navier-Stokes equations (the Oseen system of assemble(), Assembly::
// transient) solved without assembling the Q2-Q1 matrix.
//
// Kept while the mesh is: a MatrixFree object on the mesh's own constraints
// (hanging nodes, walls, pressure regions), the patterns of the few
// assembled pieces and the pressure faces' right-hand side. Per step:
//  - the grains' rigid nodes (and pinned pressures) become identity rows of
//    the operator, their values a lifting; cells whose velocity nodes are
//    all imposed are skipped (they add nothing to a free row);
//  - the coefficients at the quadrature points (BDF mass, Temam term,
//    advecting velocity) and the right-hand side from the history;
//  - the traction faces' convective term rho/2 |(w . n)_-| (u, v) and the
//    rigid-node pressure smoothing -C, assembled (faces and cut cells only);
//  - the preconditioner: FGMRES with a block upper-triangular
//    preconditioner, the velocity block (mass-dominated at the Courant
//    numbers of the injections) by a few Jacobi-GMRES iterations, the
//    Schur complement by X^-1 with X = sum over cells of B_K D^-1 B_K^T + C
//    (the pressure matrix of the least-squares commutator, element by
//    element, from reference tensors on box cells) and one AMG;
//  - the fluid force on each rigid node (and the walls) from the residual
//    F - K u of its rows, cell by cell, as compute_reactions() does.

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
#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/matrix_free_operators.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/fluid/pressure_region.h>

namespace softsand
{
  namespace fluid
  {
    namespace
    {
      /// The velocity block's inner Jacobi-GMRES: relative reduction and
      /// iterations per application (measured against 1e-2 / 20 and
      /// 3e-1 / 4 on the small Hele-Shaw scene, doc/notes/solver_study.md).
      constexpr double       velocity_inner_reduction  = 1e-1;
      constexpr unsigned int velocity_inner_iterations = 8;
      /// The pressure matrix X's CG: relative reduction and iterations.
      constexpr double       schur_reduction  = 1e-2;
      constexpr unsigned int schur_iterations = 30;

      /// Integrals of the 1D Q2 Lagrange basis (nodes 0, 1/2, 1) and the Q1
      /// basis on (0, 1): the tensor factors of the local matrices on a box.
      struct ReferenceIntegrals
      {
        double mass2[3], stiff2[3]; // int phi_i^2, int phi_i'^2
        double mixed[2][3];         // int psi_a phi_i
        double mixed_grad[2][3];    // int psi_a phi_i'
        double mass1[2][2], stiff1[2][2];

        ReferenceIntegrals()
        {
          const QGauss<1> gauss(3);
          const auto phi = [](const unsigned int i, const double x) {
            return i == 0 ? 2 * (x - 0.5) * (x - 1) :
                            (i == 1 ? -4 * x * (x - 1) : 2 * x * (x - 0.5));
          };
          const auto dphi = [](const unsigned int i, const double x) {
            return i == 0 ? 4 * x - 3 : (i == 1 ? 4 - 8 * x : 4 * x - 1);
          };
          const auto psi = [](const unsigned int a, const double x) {
            return a == 0 ? 1 - x : x;
          };
          const auto dpsi = [](const unsigned int a, const double) {
            return a == 0 ? -1. : 1.;
          };
          for (unsigned int i = 0; i < 3; ++i)
            {
              mass2[i] = stiff2[i] = 0;
              for (unsigned int a = 0; a < 2; ++a)
                mixed[a][i] = mixed_grad[a][i] = 0;
            }
          for (unsigned int a = 0; a < 2; ++a)
            for (unsigned int b = 0; b < 2; ++b)
              mass1[a][b] = stiff1[a][b] = 0;
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const double x = gauss.point(q)[0], w = gauss.weight(q);
              for (unsigned int i = 0; i < 3; ++i)
                {
                  mass2[i] += phi(i, x) * phi(i, x) * w;
                  stiff2[i] += dphi(i, x) * dphi(i, x) * w;
                  for (unsigned int a = 0; a < 2; ++a)
                    {
                      mixed[a][i] += psi(a, x) * phi(i, x) * w;
                      mixed_grad[a][i] += psi(a, x) * dphi(i, x) * w;
                    }
                }
              for (unsigned int a = 0; a < 2; ++a)
                for (unsigned int b = 0; b < 2; ++b)
                  {
                    mass1[a][b] += psi(a, x) * psi(b, x) * w;
                    stiff1[a][b] += dpsi(a, x) * dpsi(b, x) * w;
                  }
            }
        }
      };

      /// The edges of an axis-parallel box cell, or zeros for another.
      template <int dim>
      Tensor<1, dim>
      box_edges(const CellAccessor<dim, dim> &cell)
      {
        const Point<dim> origin = cell.vertex(0);
        Tensor<1, dim>   edges  = cell.vertex((1 << dim) - 1) - origin;
        for (unsigned int d = 0; d < dim; ++d)
          if (!(edges[d] > 0))
            return Tensor<1, dim>();
        for (unsigned int v = 0; v < (1u << dim); ++v)
          {
            Point<dim> expected = origin;
            for (unsigned int d = 0; d < dim; ++d)
              if (v & (1u << d))
                expected[d] += edges[d];
            if (expected.distance(cell.vertex(v)) > 1e-10 * edges.norm())
              return Tensor<1, dim>();
          }
        return edges;
      }

      /// Local tensors of one cell in the lexicographic numbering of the
      /// matrix-free kernels: per scalar Q2 function l the diagonal of the
      /// mass and of the Laplacian, per direction c the pressure-velocity
      /// coupling int psi_a d_c phi_l, and the Q1 Laplacian.
      template <int dim>
      struct LocalTensors
      {
        static constexpr unsigned int n_u = Utilities::pow(3, dim);
        static constexpr unsigned int n_p = Utilities::pow(2, dim);
        std::array<double, n_u>                      mass, stiffness;
        std::array<std::array<double, n_u>, dim * n_p> coupling; // [c*n_p+a][l]
        FullMatrix<double>                           pressure_laplace{n_p, n_p};
      };

      template <int dim>
      class LocalTensorComputer
      {
      public:
        LocalTensorComputer()
          : scalar_q2(2)
          , scalar_q1(1)
          , quadrature(3)
          , q2_values(scalar_q2,
                      quadrature,
                      update_values | update_gradients | update_JxW_values)
          , q1_values(scalar_q1, quadrature, update_values | update_gradients)
          , h2l(FETools::hierarchic_to_lexicographic_numbering<dim>(2))
        {}

        void
        compute(const typename Triangulation<dim>::active_cell_iterator &cell,
                LocalTensors<dim>                                        &t)
        {
          constexpr unsigned int n_u = LocalTensors<dim>::n_u,
                                 n_p = LocalTensors<dim>::n_p;
          const Tensor<1, dim>   h   = box_edges<dim>(*cell);
          if (h.norm() > 0)
            {
              double volume = 1;
              for (unsigned int d = 0; d < dim; ++d)
                volume *= h[d];
              for (unsigned int l = 0; l < n_u; ++l)
                {
                  unsigned int idx[dim];
                  for (unsigned int d = 0, r = l; d < dim; ++d, r /= 3)
                    idx[d] = r % 3;
                  double m = volume, s = 0;
                  for (unsigned int d = 0; d < dim; ++d)
                    m *= ref.mass2[idx[d]];
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      double term = volume / (h[c] * h[c]) * ref.stiff2[idx[c]];
                      for (unsigned int d = 0; d < dim; ++d)
                        if (d != c)
                          term *= ref.mass2[idx[d]];
                      s += term;
                    }
                  t.mass[l]      = m;
                  t.stiffness[l] = s;
                  for (unsigned int a = 0; a < n_p; ++a)
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        double term = volume / h[c];
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            const unsigned int ad = (a >> d) & 1u;
                            term *= (d == c) ? ref.mixed_grad[ad][idx[d]] :
                                               ref.mixed[ad][idx[d]];
                          }
                        t.coupling[c * n_p + a][l] = term;
                      }
                }
              for (unsigned int a = 0; a < n_p; ++a)
                for (unsigned int b = 0; b < n_p; ++b)
                  {
                    double sum = 0;
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        double term = volume / (h[c] * h[c]);
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            const unsigned int ad = (a >> d) & 1u,
                                               bd = (b >> d) & 1u;
                            term *= (d == c) ? ref.stiff1[ad][bd] :
                                               ref.mass1[ad][bd];
                          }
                        sum += term;
                      }
                    t.pressure_laplace(a, b) = sum;
                  }
              return;
            }
          // Any other cell: the same integrals with FEValues (Q1 numbers its
          // vertices lexicographically).
          q2_values.reinit(cell);
          q1_values.reinit(cell);
          for (unsigned int l = 0; l < n_u; ++l)
            {
              t.mass[l] = t.stiffness[l] = 0;
              for (unsigned int k = 0; k < dim * n_p; ++k)
                t.coupling[k][l] = 0;
            }
          t.pressure_laplace = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double JxW = q2_values.JxW(q);
              for (unsigned int b = 0; b < n_u; ++b)
                {
                  const unsigned int l   = h2l[b];
                  const double       phi = q2_values.shape_value(b, q);
                  const auto        &g   = q2_values.shape_grad(b, q);
                  t.mass[l] += phi * phi * JxW;
                  t.stiffness[l] += g * g * JxW;
                  for (unsigned int a = 0; a < n_p; ++a)
                    for (unsigned int c = 0; c < dim; ++c)
                      t.coupling[c * n_p + a][l] +=
                        q1_values.shape_value(a, q) * g[c] * JxW;
                }
              for (unsigned int a = 0; a < n_p; ++a)
                for (unsigned int b = 0; b < n_p; ++b)
                  t.pressure_laplace(a, b) += q1_values.shape_grad(a, q) *
                                              q1_values.shape_grad(b, q) * JxW;
            }
        }

      private:
        const ReferenceIntegrals  ref;
        FE_Q<dim>                 scalar_q2, scalar_q1;
        QGauss<dim>               quadrature;
        FEValues<dim>             q2_values, q1_values;
        std::vector<unsigned int> h2l;
      };


      /// The do-nothing condition's -p_b (v . n) on the face @p face_values
      /// was reinitialized on, added to @p local (the pressure faces'
      /// right-hand side, also in the walls' reaction).
      template <int dim>
      void
      add_pressure_face_term(const FEFaceValues<dim> &face_values,
                             const double             p_b,
                             Vector<double>          &local)
      {
        const FEValuesExtractors::Vector velocities(0);
        for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
          for (unsigned int i = 0; i < local.size(); ++i)
            local(i) -= p_b *
                        (face_values[velocities].value(i, q) *
                         face_values.normal_vector(q)) *
                        face_values.JxW(q);
      }


      /**
       * Block upper-triangular preconditioner of the transient matrix-free
       * step: p = -X^-1 r_p (one AMG V-cycle on X = B D^-1 B^T + C), then u
       * from A u = r_u - B^T p by a few Jacobi-preconditioned GMRES
       * iterations (A is dominated by the BDF mass at the Courant numbers
       * of the injections).
       */
      template <int dim>
      class TransientBlockPreconditioner
      {
      public:
        using VectorType      = LinearAlgebra::distributed::Vector<double>;
        using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

        TransientBlockPreconditioner(
          const StokesOperator<dim>               &stokes,
          const VectorType                        &inverse_diagonal,
          const TrilinosWrappers::SparseMatrix    &schur,
          const TrilinosWrappers::PreconditionAMG &schur_amg,
          const double                             velocity_reduction,
          const unsigned int                       velocity_iterations)
          : stokes(stokes)
          , inverse_diagonal(inverse_diagonal)
          , schur(schur)
          , schur_amg(schur_amg)
          , velocity_reduction(velocity_reduction)
          , velocity_iterations(velocity_iterations)
        {}

        void
        vmult(BlockVectorType &dst, const BlockVectorType &src) const
        {
          // X^-1 by CG with the AMG: the V-cycle alone doubled the outer
          // iterations, and X has a 25th of the unknowns.
          dst.block(1) = 0;
          {
            ReductionControl control(schur_iterations,
                                     1e-300,
                                     schur_reduction,
                                     false,
                                     false);
            SolverCG<VectorType> cg(control);
            try
              {
                cg.solve(schur, dst.block(1), src.block(1), schur_amg);
              }
            catch (const SolverControl::NoConvergence &)
              {}
            schur_cg_iterations += control.last_step();
          }
          dst.block(1) *= -1.;
          tmp.reinit(src.block(0), true);
          stokes.apply_gradient(tmp, dst.block(1));
          tmp.sadd(-1., 1., src.block(0));
          stokes.zero_constrained_velocity_rows(tmp);
          dst.block(0) = 0;
          ReductionControl control(velocity_iterations,
                                   1e-300,
                                   velocity_reduction,
                                   false,
                                   false);
          SolverGMRES<VectorType> gmres(
            control,
            typename SolverGMRES<VectorType>::AdditionalData(
              velocity_iterations + 2));
          const VelocityBlock block{stokes};
          const Jacobi        jacobi{inverse_diagonal};
          try
            {
              gmres.solve(block, dst.block(0), tmp, jacobi);
            }
          catch (const SolverControl::NoConvergence &)
            {
              // An approximate inverse is all FGMRES needs.
            }
          inner_iterations += control.last_step();
          ++inner_solves;
          stokes.zero_constrained_rows(dst);
        }

        mutable unsigned int inner_iterations = 0, inner_solves = 0,
                             schur_cg_iterations = 0;

      private:
        struct VelocityBlock
        {
          const StokesOperator<dim> &stokes;
          void
          vmult(VectorType &dst, const VectorType &src) const
          {
            stokes.vmult_velocity(dst, src);
          }
        };
        struct Jacobi
        {
          const VectorType &inverse_diagonal;
          void
          vmult(VectorType &dst, const VectorType &src) const
          {
            dst = src;
            dst.scale(inverse_diagonal);
          }
        };

        const StokesOperator<dim>               &stokes;
        const VectorType                        &inverse_diagonal;
        const TrilinosWrappers::SparseMatrix    &schur;
        const TrilinosWrappers::PreconditionAMG &schur_amg;
        const double                             velocity_reduction;
        const unsigned int                       velocity_iterations;
        mutable VectorType                       tmp;
      };
    } // namespace


    template <int dim>
    struct PenalizedNavierStokes<dim>::TransientMatrixFree
    {
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

      MappingQ1<dim> mapping;
      /// The mesh's constraints, homogeneous, split by block (hanging
      /// nodes, walls, pressure regions); the pressure ones again with the
      /// regions' pressures (the smoothing's lifting).
      AffineConstraints<double> velocity_constraints, pressure_constraints,
        pressure_values;
      std::shared_ptr<MatrixFree<dim, double>>           matrix_free;
      std::shared_ptr<VelocityCoefficients<dim, double>> coefficients;
      std::shared_ptr<VelocityOperator<dim, 2, double>>  velocity_operator;
      StokesOperator<dim>                                stokes;
      /// Per cell batch: a pressure-region (reservoir) cell; per cell batch
      /// and step: all velocity nodes imposed (skipped by vmult()).
      std::vector<unsigned char> reservoir, skip;
      /// Cells with a traction face: (batch, lane, face, subface or -1).
      std::vector<std::array<int, 4>> traction_faces;
      /// Pressure faces' right-hand side -p_b (v . n), per mesh.
      VectorType face_rhs;
      /// Per step: traction term, smoothing -C.
      TrilinosWrappers::SparseMatrix traction, smoothing;
      bool                           has_traction = false, has_smoothing = false;
      TrilinosWrappers::PreconditionAMG schur_amg;
      /// Per velocity DoF of the partitioner (owned, then ghosts), this
      /// step: bit 0 imposed (no free value), bit 1 a rigid node.
      std::vector<unsigned char> velocity_flags;
      std::vector<unsigned int>  step_velocity, step_pressure;
      VectorType                 inverse_diagonal;
      /// B^T and B with the mesh's constraints (per mesh), and the pressure
      /// matrix X = B D^-1 B^T + C of the step.
      TrilinosWrappers::SparseMatrix gradient, divergence, schur,
        schur_of_amg;
      /// The step length and BDF order X's AMG was built for, the mean
      /// CG iterations on X of that step and of the last one.
      double       schur_time_step            = 0;
      unsigned int schur_order                = 0;
      unsigned int schur_reference_iterations = 0;
      unsigned int last_iterations            = 0;
      /// This step's history and solution on the matrix-free layout.
      VectorType old_velocity, older_velocity;
      /// Body force constant in space and time (its value), or evaluated at
      /// every quadrature point.
      bool           constant_body_force = true;
      Tensor<1, dim> body_force_value;
    };


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
                                          relevant_partitioning[0]),
            transposed(dof_handler_pressure.n_dofs(),
                       dof_handler_velocity.n_dofs(),
                       relevant_partitioning[1]);
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
                data.pressure_constraints.add_entries_local_to_global(
                  p, data.velocity_constraints, u, transposed, false);
              }
          SparsityTools::distribute_sparsity_pattern(sparsity,
                                                     owned_partitioning[0],
                                                     mpi_communicator,
                                                     relevant_partitioning[0]);
          data.gradient.reinit(owned_partitioning[0],
                               owned_partitioning[1],
                               sparsity,
                               mpi_communicator);
          SparsityTools::distribute_sparsity_pattern(transposed,
                                                     owned_partitioning[1],
                                                     mpi_communicator,
                                                     relevant_partitioning[1]);
          data.divergence.reinit(owned_partitioning[1],
                                 owned_partitioning[0],
                                 transposed,
                                 mpi_communicator);
          LocalTensors<dim>        tensors;
          LocalTensorComputer<dim> computer;
          FullMatrix<double> local_gradient(u.size(), p.size()),
            local_divergence(p.size(), u.size());
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
                local_divergence.copy_transposed(local_gradient);
                data.pressure_constraints.distribute_local_to_global(
                  local_divergence,
                  p,
                  data.velocity_constraints,
                  u,
                  data.divergence);
              }
          data.gradient.compress(VectorOperation::add);
          data.divergence.compress(VectorOperation::add);
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


    template <int dim>
    unsigned int
    PenalizedNavierStokes<dim>::advance_matrix_free(const double       dt,
                                                    const unsigned int order)
    {
      using VectorType      = LinearAlgebra::distributed::Vector<double>;
      using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;
      using Evaluation = typename VelocityOperator<dim, 2, double>::Evaluation;
      if (transient_matrix_free == nullptr)
        setup_transient_matrix_free();
      TransientMatrixFree           &data        = *transient_matrix_free;
      const MatrixFree<dim, double> &matrix_free = *data.matrix_free;
      const types::global_dof_index  n_u = dof_handler_velocity.n_dofs();
      const unsigned int             n_batches = matrix_free.n_cell_batches();
      const double rho = fluid_parameters.density;
      const double mu  = fluid_parameters.viscosity;
      const BDFCoefficients bdf = bdf_coefficients(order, bdf_step_ratio);
      const bool            penalized = solid_field != nullptr && !rigid_nodes();
      constexpr unsigned int n_p = LocalTensors<dim>::n_p;
      constexpr unsigned int n_q = Utilities::pow(3, dim);
      // The right-hand side of assemble() at a point x:
      // f - rho* / dt (a1 u~^n + a2 u~^(n-1)), u~ = vf u + (1 - vf) u_s.
      const auto right_hand_side = [&](const Point<dim>     &x,
                                       const Tensor<1, dim> &u_old,
                                       const Tensor<1, dim> &u_older,
                                       const double          vf,
                                       const Tensor<1, dim> &u_s) {
        Tensor<1, dim> f = transient_matrix_free->body_force_value;
        if (!transient_matrix_free->constant_body_force)
          {
            Vector<double> value(dim);
            body_force->vector_value(x, value);
            for (unsigned int d = 0; d < dim; ++d)
              f[d] = value[d];
          }
        const double solid    = 1. - vf;
        const double rho_star = rho * (1. + fluid_parameters.theta * solid);
        return Tensor<1, dim>(
          f - rho_star / dt *
                (bdf.a1 * (vf * u_old + solid * u_s) +
                 bdf.a2 * (vf * u_older + solid * u_s)));
      };
      const auto &partitioner_u = *matrix_free.get_vector_partitioner(0);
      const auto &partitioner_p = *matrix_free.get_vector_partitioner(1);
      const unsigned int owned_u = partitioner_u.locally_owned_size();
      const unsigned int owned_p = partitioner_p.locally_owned_size();

      bool            rebuilt_schur = false;
      BlockVectorType rhs, lifting, delta;
      for (BlockVectorType *v : {&rhs, &lifting, &delta})
        {
          v->reinit(2);
          matrix_free.initialize_dof_vector(v->block(0), 0);
          matrix_free.initialize_dof_vector(v->block(1), 1);
          v->collect_sizes();
        }
      {
        TimerOutput::Scope t(timer, "fluid: assemble");

        // This step's constraints: imposed and rigid velocity nodes, the
        // rows only this step constrains (grains), and the lifting that
        // carries every constrained value.
        data.velocity_flags.assign(owned_u + partitioner_u.n_ghost_indices(),
                                   0);
        data.step_velocity.clear();
        data.step_pressure.clear();
        for (const auto &line : constraints.get_lines())
          if (line.index < n_u)
            {
              if (!partitioner_u.in_local_range(line.index) &&
                  !partitioner_u.is_ghost_entry(line.index))
                continue;
              const unsigned int i = partitioner_u.global_to_local(line.index);
              if (line.entries.empty())
                data.velocity_flags[i] |= 1;
              if (i < owned_u)
                {
                  lifting.block(0).local_element(i) = line.inhomogeneity;
                  if (!data.velocity_constraints.is_constrained(line.index))
                    data.step_velocity.push_back(i);
                }
            }
          else
            {
              const types::global_dof_index g = line.index - n_u;
              if (!partitioner_p.in_local_range(g))
                continue;
              const unsigned int i = partitioner_p.global_to_local(g);
              lifting.block(1).local_element(i) = line.inhomogeneity;
              if (!data.pressure_constraints.is_constrained(g))
                data.step_pressure.push_back(i);
            }
        for (const auto &[i, grain] : rigid_dof_grain)
          if (partitioner_u.in_local_range(i) || partitioner_u.is_ghost_entry(i))
            data.velocity_flags[partitioner_u.global_to_local(i)] |= 2;

        // The history on the kernels' layout.
        const auto copy_velocity = [&](const BlockVector &from,
                                       VectorType        &to) {
          matrix_free.initialize_dof_vector(to, 0);
          for (unsigned int i = 0; i < owned_u; ++i)
            to.local_element(i) =
              from.block(0)(partitioner_u.local_to_global(i));
          to.update_ghost_values();
        };
        copy_velocity(old_solution, data.old_velocity);
        if (order == 2)
          copy_velocity(older_solution, data.older_velocity);
        else
          data.older_velocity.reinit(0);

        // Coefficients at the quadrature points and the right-hand side.
        auto &coefficients = *data.coefficients;
        coefficients.reaction.reinit(n_batches, n_q);
        coefficients.advection.reinit(n_batches, n_q);
        coefficients.viscosity_scale.resize(0);
        coefficients.viscosity_scale.resize(n_batches,
                                            VectorizedArray<double>(1.));
        data.skip.assign(n_batches, 0);
        Evaluation phi(matrix_free, 0, 0), phi_old(matrix_free, 0, 0),
          phi_older(matrix_free, 0, 0);
        std::vector<types::global_dof_index> u_dofs(
          fe_velocity.n_dofs_per_cell());
        std::vector<Point<dim>>     points(n_q);
        std::vector<double>         void_fraction(n_q, 1.);
        std::vector<Tensor<1, dim>> solid_velocity(n_q);
        std::vector<int>            solid_index(n_q, -1);
        Vector<double>              force_value(dim);
        AlignedVector<Tensor<1, dim, VectorizedArray<double>>> rhs_values(n_q);
        for (unsigned int batch = 0; batch < n_batches; ++batch)
          {
            // Skipped: every velocity node of every lane imposed.
            bool all_fixed = true;
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch) &&
                 all_fixed;
                 ++lane)
              {
                matrix_free.get_cell_iterator(batch, lane, 0)
                  ->get_dof_indices(u_dofs);
                for (const auto i : u_dofs)
                  if (!(data.velocity_flags[partitioner_u.global_to_local(i)] &
                        1))
                    {
                      all_fixed = false;
                      break;
                    }
              }
            data.skip[batch] = all_fixed;
            if (data.reservoir[batch])
              {
                // Only the pressure term -(p, div v) (PressureRegion).
                coefficients.viscosity_scale[batch] = 0.;
                for (unsigned int q = 0; q < n_q; ++q)
                  {
                    coefficients.reaction(batch, q)  = 0.;
                    coefficients.advection(batch, q) =
                      Tensor<1, dim, VectorizedArray<double>>();
                  }
                continue;
              }
            phi.reinit(batch);
            phi_old.reinit(batch);
            phi_old.read_dof_values_plain(data.old_velocity);
            phi_old.evaluate(EvaluationFlags::values |
                             EvaluationFlags::gradients);
            if (order == 2)
              {
                phi_older.reinit(batch);
                phi_older.read_dof_values_plain(data.older_velocity);
                phi_older.evaluate(EvaluationFlags::values |
                                   EvaluationFlags::gradients);
              }
            for (unsigned int lane = 0;
                 lane < matrix_free.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                for (unsigned int q = 0; q < n_q; ++q)
                  for (unsigned int d = 0; d < dim; ++d)
                    points[q][d] = phi.quadrature_point(q)[d][lane];
                if (penalized)
                  evaluate_solids(*matrix_free.get_cell_iterator(batch, lane, 0),
                                  points,
                                  void_fraction,
                                  solid_velocity,
                                  solid_index);
                for (unsigned int q = 0; q < n_q; ++q)
                  {
                    Tensor<1, dim> u_old, u_older;
                    double         div_old = 0, div_older = 0;
                    const auto     value   = phi_old.get_value(q);
                    const auto     grad    = phi_old.get_gradient(q);
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        u_old[d] = value[d][lane];
                        div_old += grad[d][d][lane];
                      }
                    if (order == 2)
                      {
                        const auto v2 = phi_older.get_value(q);
                        const auto g2 = phi_older.get_gradient(q);
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            u_older[d] = v2[d][lane];
                            div_older += g2[d][d][lane];
                          }
                      }
                    const double vf    = void_fraction[q];
                    const double solid = 1. - vf;
                    const double rho_star =
                      rho * (1. + fluid_parameters.theta * solid);
                    const Tensor<1, dim> w =
                      bdf.e1 * u_old + bdf.e2 * u_older;
                    const double div_w = bdf.e1 * div_old + bdf.e2 * div_older;
                    coefficients.reaction(batch, q)[lane] =
                      bdf.a0 * rho_star / dt + 0.5 * rho * div_w;
                    for (unsigned int d = 0; d < dim; ++d)
                      coefficients.advection(batch, q)[d][lane] = rho * w[d];
                    const Tensor<1, dim> right = right_hand_side(
                      points[q], u_old, u_older, vf, solid_velocity[q]);
                    for (unsigned int d = 0; d < dim; ++d)
                      rhs_values[q][d][lane] = right[d];
                  }
              }
            for (unsigned int q = 0; q < n_q; ++q)
              phi.submit_value(rhs_values[q], q);
            phi.integrate_scatter(EvaluationFlags::values, rhs.block(0));
          }
        rhs.block(0).compress(VectorOperation::add);
        rhs.block(0) += data.face_rhs;
        data.velocity_operator->reinit(data.matrix_free,
                                       data.coefficients,
                                       data.velocity_constraints,
                                       0,
                                       0);

        // Traction faces: rho/2 |(w . n)_-| (u, v) with this step's w.
        if (data.has_traction)
          {
            data.traction = 0;
            const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
            FEFaceValues<dim>                face_values(data.mapping,
                                          fe_velocity,
                                          face_quadrature,
                                          update_values |
                                            update_normal_vectors |
                                            update_JxW_values);
            FESubfaceValues<dim>             subface_values(data.mapping,
                                                fe_velocity,
                                                face_quadrature,
                                                update_values |
                                                  update_normal_vectors |
                                                  update_JxW_values);
            const FEValuesExtractors::Vector velocities(0);
            FullMatrix<double> local(fe_velocity.n_dofs_per_cell(),
                                     fe_velocity.n_dofs_per_cell());
            std::vector<Tensor<1, dim>> w(face_quadrature.size()),
              w_older(face_quadrature.size());
            for (const auto &[batch, lane, f, sf] : data.traction_faces)
              {
                const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
                const FEFaceValuesBase<dim> &values =
                  sf < 0 ? static_cast<const FEFaceValuesBase<dim> &>(
                             face_values) :
                           static_cast<const FEFaceValuesBase<dim> &>(
                             subface_values);
                if (sf < 0)
                  face_values.reinit(cell, f);
                else
                  subface_values.reinit(cell, f, sf);
                values[velocities].get_function_values(data.old_velocity, w);
                if (order == 2)
                  {
                    values[velocities].get_function_values(
                      data.older_velocity, w_older);
                    for (unsigned int q = 0; q < w.size(); ++q)
                      w[q] = bdf.e1 * w[q] + bdf.e2 * w_older[q];
                  }
                local = 0;
                for (unsigned int q = 0; q < w.size(); ++q)
                  {
                    const double w_n = w[q] * values.normal_vector(q);
                    if (w_n >= 0)
                      continue;
                    const double weight = -0.5 * rho * w_n * values.JxW(q);
                    for (unsigned int i = 0; i < local.m(); ++i)
                      {
                        const double phi_i = values.shape_value(i, q);
                        if (phi_i == 0)
                          continue;
                        const unsigned int ci =
                          fe_velocity.system_to_component_index(i).first;
                        for (unsigned int j = 0; j < local.n(); ++j)
                          if (fe_velocity.system_to_component_index(j).first ==
                              ci)
                            local(i, j) +=
                              weight * phi_i * values.shape_value(j, q);
                      }
                  }
                cell->get_dof_indices(u_dofs);
                data.velocity_constraints.distribute_local_to_global(
                  local, u_dofs, data.traction);
              }
            data.traction.compress(VectorOperation::add);
          }

        // The rigid-node pressure smoothing -C in cut cells, lifted with
        // the regions' pressures.
        LocalTensors<dim>        local_tensors;
        LocalTensorComputer<dim> tensor_computer;
        std::vector<types::global_dof_index> p_dofs(n_p);
        if (data.has_smoothing)
          {
            data.smoothing = 0;
            FullMatrix<double> local(n_p, n_p);
            Vector<double>     local_rhs(n_p);
            for (unsigned int batch = 0; batch < n_batches; ++batch)
              for (unsigned int lane = 0;
                   lane < matrix_free.n_active_entries_per_cell_batch(batch);
                   ++lane)
                {
                  const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
                  cell->get_dof_indices(u_dofs);
                  unsigned int n_rigid = 0, n_fixed = 0;
                  for (const auto i : u_dofs)
                    {
                      const unsigned char flag =
                        data.velocity_flags[partitioner_u.global_to_local(i)];
                      n_rigid += (flag & 2) ? 1 : 0;
                      n_fixed += (flag & 1) ? 1 : 0;
                    }
                  if (n_rigid == 0)
                    continue;
                  const double h = cell->diameter() / std::sqrt(double(dim));
                  const double weight =
                    rigid_cell_weights(u_dofs.size(), n_rigid, n_fixed, h)
                      .second;
                  if (weight == 0)
                    continue;
                  tensor_computer.compute(cell, local_tensors);
                  for (unsigned int a = 0; a < n_p; ++a)
                    for (unsigned int b = 0; b < n_p; ++b)
                      local(a, b) =
                        -weight * local_tensors.pressure_laplace(a, b);
                  local_rhs = 0;
                  matrix_free.get_cell_iterator(batch, lane, 1)
                    ->get_dof_indices(p_dofs);
                  data.pressure_values.distribute_local_to_global(
                    local, local_rhs, p_dofs, data.smoothing, rhs.block(1));
                }
            data.smoothing.compress(VectorOperation::add);
            rhs.block(1).compress(VectorOperation::add);
          }
        data.stokes.reinit(data.matrix_free,
                           data.velocity_operator,
                           data.velocity_constraints,
                           data.pressure_constraints,
                           data.has_smoothing ? &data.smoothing : nullptr);
        data.stokes.set_step_data(&data.skip,
                                  data.step_velocity,
                                  data.step_pressure,
                                  data.has_traction ? &data.traction : nullptr);

        // The lifting: rhs -= K g for the constrained values g (the cell
        // terms read plainly; the traction term through its matrix).
        lifting.update_ghost_values();
        data.stokes.subtract_plain(rhs, lifting);
        if (data.has_traction)
          {
            VectorType tmp;
            tmp.reinit(rhs.block(0), true);
            data.traction.vmult(tmp, lifting.block(0));
            rhs.block(0) -= tmp;
          }
        data.stokes.zero_constrained_rows(rhs);

        if (!boundary_conditions.has_pressure_face())
          {
            // As solve_linear(): project the continuity rows onto the range.
            std::vector<bool> constrained(owned_p, false);
            for (const auto &line : data.pressure_constraints.get_lines())
              if (partitioner_p.in_local_range(line.index))
                constrained[partitioner_p.global_to_local(line.index)] = true;
            for (const auto i : data.step_pressure)
              constrained[i] = true;
            double       sum   = 0;
            unsigned int count = 0;
            for (unsigned int i = 0; i < owned_p; ++i)
              if (!constrained[i])
                {
                  sum += rhs.block(1).local_element(i);
                  ++count;
                }
            sum   = Utilities::MPI::sum(sum, mpi_communicator);
            count = Utilities::MPI::sum(count, mpi_communicator);
            for (unsigned int i = 0; i < owned_p; ++i)
              if (!constrained[i])
                rhs.block(1).local_element(i) -= sum / count;
          }
      }

      {
        TimerOutput::Scope t(timer, "fluid: preconditioner setup");
        // D = diag(A) from each cell's mass and Laplacian diagonals with the
        // cell's mean coefficients (1 on imposed rows), and the pressure
        // matrix X = B D^-1 B^T + C of the least-squares commutator with
        // the mesh's B (an element-by-element X, sum_K B_K D^-1 B_K^T, cost
        // 40-80 FGMRES iterations instead of 10-14: doc/notes/solver_study.md).
        matrix_free.initialize_dof_vector(data.inverse_diagonal, 0);
        const auto &coefficients = *data.coefficients;
        std::vector<types::global_dof_index> u_dofs(
          fe_velocity.n_dofs_per_cell());
        const std::vector<unsigned int> h2l =
          FETools::hierarchic_to_lexicographic_numbering<dim>(2);
        LocalTensors<dim>        tensors;
        LocalTensorComputer<dim> tensor_computer;
        for (unsigned int batch = 0; batch < n_batches; ++batch)
          for (unsigned int lane = 0;
               lane < matrix_free.n_active_entries_per_cell_batch(batch);
               ++lane)
            {
              if (data.skip[batch])
                continue;
              const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
              double     beta = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                beta += coefficients.reaction(batch, q)[lane];
              beta /= n_q;
              const double viscosity =
                mu * coefficients.viscosity_scale[batch][lane];
              tensor_computer.compute(cell, tensors);
              cell->get_dof_indices(u_dofs);
              for (unsigned int i = 0; i < u_dofs.size(); ++i)
                {
                  const unsigned int l =
                    h2l[fe_velocity.system_to_component_index(i).second];
                  data.inverse_diagonal.local_element(
                    partitioner_u.global_to_local(u_dofs[i])) +=
                    beta * tensors.mass[l] + viscosity * tensors.stiffness[l];
                }
            }
        data.inverse_diagonal.compress(VectorOperation::add);
        // X takes 1 / D of every node that is not imposed.
        TrilinosWrappers::MPI::Vector weights(owned_partitioning[0],
                                              mpi_communicator);
        for (unsigned int i = 0; i < owned_u; ++i)
          {
            const double d = data.inverse_diagonal.local_element(i);
            weights(partitioner_u.local_to_global(i)) =
              ((data.velocity_flags[i] & 1) || !(std::abs(d) > 0)) ? 0. :
                                                                      1. / d;
          }
        for (const auto i : data.step_velocity)
          weights(partitioner_u.local_to_global(i)) = 0.;
        weights.compress(VectorOperation::insert);
        {
          std::vector<bool> unit(owned_u, false);
          for (const auto &line : data.velocity_constraints.get_lines())
            if (partitioner_u.in_local_range(line.index))
              unit[partitioner_u.global_to_local(line.index)] = true;
          for (unsigned int i = 0; i < owned_u; ++i)
            {
              double &d = data.inverse_diagonal.local_element(i);
              d         = (unit[i] || (data.velocity_flags[i] & 1) ||
                   !(std::abs(d) > 0)) ?
                            1. :
                            1. / d;
            }
          for (const auto i : data.step_velocity)
            data.inverse_diagonal.local_element(i) = 1.;
        }
        data.inverse_diagonal.update_ghost_values();

        // X is formed every step (kept from the last step, it doubled the
        // FGMRES iterations on the small Hele-Shaw scene); its AMG is kept
        // over steps of the same length and order (a preconditioner of
        // the inner CG) until that CG needs twice the iterations it took
        // when the AMG was built.
        rebuilt_schur = data.schur.m() == 0 || dt != data.schur_time_step ||
                        order != data.schur_order ||
                        data.last_iterations >
                          2 * data.schur_reference_iterations + 1;
        {
            data.schur_time_step = dt;
            data.schur_order     = order;
            TrilinosWrappers::SparseMatrix product;
            data.divergence.mmult(product, data.gradient, weights);
            discrete_brinkman_from_product(product,
                                           data.has_smoothing ?
                                             &data.smoothing :
                                             nullptr,
                                           data.schur);
            TrilinosWrappers::PreconditionAMG::AdditionalData amg;
            amg.elliptic              = true;
            amg.higher_order_elements = false;
            amg.smoother_sweeps       = 2;
            amg.aggregation_threshold = 0.02;
            if (rebuilt_schur)
              {
                // ML keeps a reference to its matrix: a copy of X of this
                // step, which the next steps' X does not replace.
                data.schur_amg.clear();
                data.schur_of_amg.copy_from(data.schur);
                data.schur_amg.initialize(data.schur_of_amg, amg);
              }
          }
      }

      {
      TimerOutput::Scope t(timer, "fluid: solve");
      // Start from the previous state (correction form, zero on every
      // constrained row).
      {
        for (unsigned int i = 0; i < owned_u; ++i)
          delta.block(0).local_element(i) =
            solution.block(0)(partitioner_u.local_to_global(i));
        for (unsigned int i = 0; i < owned_p; ++i)
          delta.block(1).local_element(i) =
            solution.block(1)(partitioner_p.local_to_global(i));
        data.stokes.zero_constrained_rows(delta);
      }
      const double  rhs_norm = rhs.l2_norm();
      SolverControl control(
        solver_parameters.max_linear_iterations,
        std::max(solver_parameters.linear_tolerance * rhs_norm, 1e-300),
        false,
        false);
      // The velocity block's inner solve: a loose Jacobi-GMRES (FGMRES is
      // flexible; tighter inner solves cost more than the outer iterations
      // they save, doc/notes/solver_study.md).
      const TransientBlockPreconditioner<dim> preconditioner(
        data.stokes,
        data.inverse_diagonal,
        data.schur,
        data.schur_amg,
        velocity_inner_reduction,
        velocity_inner_iterations);
      SolverFGMRES<BlockVectorType> solver(
        control,
        typename SolverFGMRES<BlockVectorType>::AdditionalData(
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
      const unsigned int iterations = rhs_norm > 0 ? control.last_step() : 0;
      data.last_iterations =
        preconditioner.schur_cg_iterations /
        std::max(preconditioner.inner_solves, 1u);
      if (rebuilt_schur)
        data.schur_reference_iterations = data.last_iterations;
      if (preconditioner.inner_solves > 0)
        pcout << "      matrix-free step: " << iterations
              << " FGMRES iterations, velocity GMRES "
              << preconditioner.inner_iterations / preconditioner.inner_solves
              << " per application, X CG "
              << preconditioner.schur_cg_iterations / preconditioner.inner_solves
              << (rebuilt_schur ? " (AMG rebuilt)" : "") << ", "
              << matrix_free.n_cell_batches() << " cell batches, "
              << std::count(data.skip.begin(), data.skip.end(), 1)
              << " skipped" << std::endl;

      BlockVector x(owned_partitioning, mpi_communicator);
      for (unsigned int i = 0; i < owned_u; ++i)
        x.block(0)(partitioner_u.local_to_global(i)) =
          delta.block(0).local_element(i);
      for (unsigned int i = 0; i < owned_p; ++i)
        x.block(1)(partitioner_p.local_to_global(i)) =
          delta.block(1).local_element(i);
      x.compress(VectorOperation::insert);
      accept_linear_solution(x, iterations);
      rhs.reinit(0);
      lifting.reinit(0);
      delta.reinit(0);
      }
      // The Krylov bases stay in deal.II's vector pools after a solve (two
      // block vectors per FGMRES iteration, 350 B per DoF at 22
      // iterations): give them back, or they sit beside the next step's X
      // and its product, the step's peak (doc/notes/solver_study.md).
      GrowingVectorMemory<BlockVectorType>::release_unused_memory();
      GrowingVectorMemory<VectorType>::release_unused_memory();

      // Reactions: F - K u of the rigid nodes' rows (and of the hanging
      // nodes of rigid parents, split by their weights) and the residual
      // summed over the rows of velocity-constrained boundary faces, from
      // each cell's own terms as compute_reactions() (no second assembly).
      {
        TimerOutput::Scope t(timer, "fluid: reactions");
        rigid_reactions.clear();
        // (grain, node) -> the node's position and reaction.
        struct GrainNodeHash
        {
          std::size_t
          operator()(const std::pair<int, types::global_dof_index> &k) const
          {
            return std::hash<types::global_dof_index>()(k.second) * 31 +
                   std::hash<int>()(k.first);
          }
        };
        std::unordered_map<std::pair<int, types::global_dof_index>,
                           std::pair<Point<dim>, Tensor<1, dim>>,
                           GrainNodeHash>
          node_reactions;
        node_reactions.reserve(rigid_dof_grain.size() / dim +
                               hanging_rigid_parents.size());
        VectorType u_full, p_full;
        matrix_free.initialize_dof_vector(u_full, 0);
        matrix_free.initialize_dof_vector(p_full, 1);
        for (unsigned int i = 0; i < owned_u; ++i)
          u_full.local_element(i) =
            solution.block(0)(partitioner_u.local_to_global(i));
        for (unsigned int i = 0; i < owned_p; ++i)
          p_full.local_element(i) =
            solution.block(1)(partitioner_p.local_to_global(i));
        u_full.update_ghost_values();
        p_full.update_ghost_values();
        VectorType traction_force;
        if (data.has_traction)
          {
            matrix_free.initialize_dof_vector(traction_force, 0);
            data.traction.vmult(traction_force, u_full);
            traction_force.update_ghost_values();
          }

        const std::vector<unsigned int> h2l =
          FETools::hierarchic_to_lexicographic_numbering<dim>(2);
        const unsigned int n_scalar = h2l.size();
        Evaluation         u(matrix_free, 0, 0), u_old(matrix_free, 0, 0),
          u_older(matrix_free, 0, 0);
        FEEvaluation<dim, 1, 3, 1, double> p(matrix_free, 1, 0);
        const Quadrature<dim> nodes(fe_velocity.get_unit_support_points());
        FEValues<dim>         node_values(data.mapping,
                                  fe_velocity,
                                  nodes,
                                  update_quadrature_points);
        std::vector<types::global_dof_index> u_dofs(
          fe_velocity.n_dofs_per_cell());
        std::vector<bool> on_face(fe_velocity.n_dofs_per_cell());
        std::vector<Point<dim>>     points(n_q);
        std::vector<double>         void_fraction(n_q, 1.);
        std::vector<Tensor<1, dim>> solid_velocity(n_q);
        std::vector<int>            solid_index(n_q, -1);
        Vector<double>              force_value(dim);
        Tensor<1, dim>              boundary_force;
        const bool hanging_rigid = !hanging_rigid_parents.empty();
        std::map<types::global_dof_index, std::pair<unsigned int, Point<dim>>>
          owned_rigid_nodes;
        const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
        FEFaceValues<dim>                face_values(data.mapping,
                                      fe_velocity,
                                      face_quadrature,
                                      update_values | update_normal_vectors |
                                        update_JxW_values);
        Vector<double> face_term(fe_velocity.n_dofs_per_cell());
        for (unsigned int batch = 0; batch < n_batches; ++batch)
          for (unsigned int lane = 0;
               lane < matrix_free.n_active_entries_per_cell_batch(batch);
               ++lane)
            {
              const auto cell = matrix_free.get_cell_iterator(batch, lane, 0);
              cell->get_dof_indices(u_dofs);
              bool has_rigid = false;
              for (const auto i : u_dofs)
                if ((data.velocity_flags[partitioner_u.global_to_local(i)] &
                     2) ||
                    (hanging_rigid && hanging_rigid_parents.count(i)))
                  {
                    has_rigid = true;
                    break;
                  }
              std::fill(on_face.begin(), on_face.end(), false);
              bool on_wall = false;
              for (const auto f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    boundary_conditions.imposes_velocity(
                      cell->face(f)->boundary_id()))
                  {
                    on_wall = true;
                    for (unsigned int k = 0;
                         k < fe_velocity.n_dofs_per_face();
                         ++k)
                      on_face[fe_velocity.face_to_cell_index(k, f)] = true;
                  }
              if (!has_rigid && !on_wall)
                continue;

              // The cell's K u - F, lexicographic per component.
              u.reinit(batch);
              p.reinit(batch);
              u.read_dof_values_plain(u_full);
              p.read_dof_values_plain(p_full);
              u.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
              p.evaluate(EvaluationFlags::values);
              const bool reservoir = data.reservoir[batch];
              if (!reservoir)
                {
                  u_old.reinit(batch);
                  u_old.read_dof_values_plain(data.old_velocity);
                  u_old.evaluate(EvaluationFlags::values);
                  if (order == 2)
                    {
                      u_older.reinit(batch);
                      u_older.read_dof_values_plain(data.older_velocity);
                      u_older.evaluate(EvaluationFlags::values);
                    }
                  for (unsigned int q = 0; q < n_q; ++q)
                    for (unsigned int d = 0; d < dim; ++d)
                      points[q][d] = u.quadrature_point(q)[d][lane];
                  if (penalized)
                    evaluate_solids(*cell,
                                    points,
                                    void_fraction,
                                    solid_velocity,
                                    solid_index);
                }
              Tensor<1, dim, VectorizedArray<double>> force;
              Tensor<2, dim, VectorizedArray<double>> flux;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const auto grad = u.get_gradient(q);
                  data.velocity_operator->quadrature_terms(
                    batch, q, u.get_value(q), grad, force, flux);
                  const auto pressure = p.get_value(q);
                  for (unsigned int d = 0; d < dim; ++d)
                    flux[d][d] -= pressure;
                  if (!reservoir)
                    {
                      // Minus the right-hand side of assemble().
                      Tensor<1, dim> u_o, u_oo;
                      const auto     v1 = u_old.get_value(q);
                      for (unsigned int d = 0; d < dim; ++d)
                        u_o[d] = v1[d][lane];
                      if (order == 2)
                        {
                          const auto v2 = u_older.get_value(q);
                          for (unsigned int d = 0; d < dim; ++d)
                            u_oo[d] = v2[d][lane];
                        }
                      const Tensor<1, dim> right = right_hand_side(
                        points[q], u_o, u_oo, void_fraction[q],
                        solid_velocity[q]);
                      for (unsigned int d = 0; d < dim; ++d)
                        force[d][lane] -= right[d];
                    }
                  u.submit_value(force, q);
                  u.submit_gradient(flux, q);
                }
              u.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
              const auto residual = [&](const unsigned int i) {
                const auto [c, b] = fe_velocity.system_to_component_index(i);
                return -u.begin_dof_values()[c * n_scalar + h2l[b]][lane];
              };

              if (has_rigid)
                {
                  node_values.reinit(cell);
                  for (unsigned int i = 0; i < u_dofs.size(); ++i)
                    {
                      const auto node = rigid_dof_grain.find(u_dofs[i]);
                      const auto hanging =
                        hanging_rigid ? hanging_rigid_parents.find(u_dofs[i]) :
                                        hanging_rigid_parents.end();
                      if (node == rigid_dof_grain.end() &&
                          hanging == hanging_rigid_parents.end())
                        continue;
                      const auto [c, base] =
                        fe_velocity.system_to_component_index(i);
                      const double r = residual(i);
                      // One record per grain and node (its first
                      // component's DoF): a node's cells and components
                      // sum into it, as they do in the grain's force and
                      // torque.
                      const types::global_dof_index node_key =
                        u_dofs[fe_velocity.component_to_system_index(0, base)];
                      const auto add = [&](const int grain, const double w) {
                        node_reactions
                          .try_emplace(std::make_pair(grain, node_key),
                                       node_values.quadrature_point(i),
                                       Tensor<1, dim>())
                          .first->second.second[c] += w * r;
                      };
                      if (node != rigid_dof_grain.end())
                        {
                          add(node->second, 1.);
                          if (data.has_traction &&
                              partitioner_u.in_local_range(u_dofs[i]))
                            owned_rigid_nodes.emplace(
                              u_dofs[i],
                              std::make_pair(c,
                                             node_values.quadrature_point(i)));
                        }
                      if (hanging != hanging_rigid_parents.end())
                        for (const auto &[parent, weight] : hanging->second)
                          add(rigid_dof_grain.at(parent), weight);
                    }
                }
              if (on_wall)
                {
                  for (unsigned int i = 0; i < u_dofs.size(); ++i)
                    if (on_face[i])
                      boundary_force[fe_velocity.system_to_component_index(i)
                                       .first] += residual(i);
                  // The pressure faces' -p_b (v . n) in those rows' F.
                  for (const auto f : cell->face_indices())
                    if (cell->face(f)->at_boundary() &&
                        boundary_conditions.face(cell->face(f)->boundary_id())
                            .type == BoundaryConditions<dim>::Type::pressure)
                      {
                        const double p_b =
                          boundary_conditions
                            .face(cell->face(f)->boundary_id())
                            .pressure;
                        face_values.reinit(cell, f);
                        face_term = 0;
                        add_pressure_face_term(face_values, p_b, face_term);
                        for (unsigned int i = 0; i < u_dofs.size(); ++i)
                          if (on_face[i])
                            boundary_force
                              [fe_velocity.system_to_component_index(i)
                                 .first] += face_term(i);
                      }
                }
            }
        rigid_reactions.reserve(node_reactions.size());
        for (const auto &[key, reaction] : node_reactions)
          rigid_reactions.emplace_back(key.first,
                                       reaction.first,
                                       reaction.second);
        node_reactions.clear();
        // The traction faces' term acts on rows, not cells: the rigid
        // nodes' share once per owned node, at the node.
        if (data.has_traction)
          for (const auto &[i, node] : owned_rigid_nodes)
            {
              const double r =
                traction_force.local_element(partitioner_u.global_to_local(i));
              if (r != 0)
                {
                  Tensor<1, dim> f;
                  f[node.first] = -r;
                  rigid_reactions.emplace_back(rigid_dof_grain.at(i),
                                               node.second,
                                               f);
                }
            }
        boundary_force += pressure_face_force();
        last_boundary_force =
          Utilities::MPI::sum(boundary_force, mpi_communicator);
      }
      return statistics.linear_iterations;
    }


    template void
    PenalizedNavierStokes<2>::setup_transient_matrix_free();
    template void
    PenalizedNavierStokes<3>::setup_transient_matrix_free();
    template unsigned int
    PenalizedNavierStokes<2>::advance_matrix_free(const double,
                                                  const unsigned int);
    template unsigned int
    PenalizedNavierStokes<3>::advance_matrix_free(const double,
                                                  const unsigned int);
  } // namespace fluid
} // namespace softsand
