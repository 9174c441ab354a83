// What the transient matrix-free step of PenalizedNavierStokes keeps:
// per mesh (set up by transient_matrix_free_setup.cc) and per step (the
// step's phases: transient_matrix_free.cc, transient_matrix_free_solve.cc,
// transient_matrix_free_reactions.cc).
#ifndef softsand_fluid_transient_matrix_free_h
#define softsand_fluid_transient_matrix_free_h

#include <deal.II/base/function.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <deal.II/matrix_free/matrix_free.h>

#include <softsand/fluid/bdf_coefficients.h>
#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/matrix_free_operators.h>
#include <softsand/fluid/penalized_navier_stokes.h>

#include <array>
#include <memory>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    namespace internal
    {
      using namespace dealii;

      /// The right-hand side of assemble() at a point x:
      /// f - rho* / dt (a1 u~^n + a2 u~^(n-1)), u~ = vf u + (1 - vf) u_s,
      /// rho* = rho (1 + Theta (1 - vf)).
      template <int dim>
      struct StepRightHandSide
      {
        double          rho = 0, theta = 0, dt = 1;
        BDFCoefficients bdf{};
        /// Evaluated at every point when set; else constant_force.
        const Function<dim> *body_force = nullptr;
        Tensor<1, dim>       constant_force;

        Tensor<1, dim>
        operator()(const Point<dim>     &x,
                   const Tensor<1, dim> &u_old,
                   const Tensor<1, dim> &u_older,
                   const double          vf,
                   const Tensor<1, dim> &u_s) const
        {
          Tensor<1, dim> f = constant_force;
          if (body_force != nullptr)
            {
              Vector<double> value(dim);
              body_force->vector_value(x, value);
              for (unsigned int d = 0; d < dim; ++d)
                f[d] = value[d];
            }
          const double solid    = 1. - vf;
          const double rho_star = rho * (1. + theta * solid);
          return Tensor<1, dim>(
            f - rho_star / dt *
                  (bdf.a1 * (vf * u_old + solid * u_s) +
                   bdf.a2 * (vf * u_older + solid * u_s)));
        }
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
    } // namespace internal


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
      /// step: bit 0 imposed (no free value), bit 1 a rigid node, bit 2 a
      /// hanging node on rigid parents.
      std::vector<unsigned char> velocity_flags;
      std::vector<unsigned int>  step_velocity, step_pressure;
      VectorType                 inverse_diagonal;
      /// B^T and B with the mesh's constraints (per mesh; the step scales
      /// B^T's rows by D^-1 in place), and the pressure matrix
      /// X = B D^-1 B^T + C of the step, whose pattern is kept per mesh.
      TrilinosWrappers::SparseMatrix gradient, divergence, schur,
        schur_of_amg;
      /// B^T's values as assembled, in the order of its local rows, in
      /// single precision (X is a preconditioner's; this halves the copy).
      std::vector<float> gradient_values;
      /// Forms X's values per step on the patterns of the mesh's first.
      DiscreteBrinkmanProduct schur_product;
      /// The step length and BDF order X's AMG was built for, the mean
      /// CG iterations on X of that step and of the last one.
      double       schur_time_step            = 0;
      unsigned int schur_order                = 0;
      unsigned int schur_reference_iterations = 0;
      unsigned int last_iterations            = 0;
      /// This step's history on the matrix-free layout.
      VectorType old_velocity, older_velocity;
      /// This step's right-hand side and the lifting of its constrained
      /// values (released after the solve).
      BlockVectorType rhs, lifting;
      /// Whether this step rebuilt X's AMG.
      bool rebuilt_schur = false;
      /// Body force constant in space and time (its value), or evaluated at
      /// every quadrature point.
      bool           constant_body_force = true;
      Tensor<1, dim> body_force_value;
      /// The BDF right-hand side of this step, by point.
      internal::StepRightHandSide<dim> right_hand_side;

      /// @p to = block @p block (0 velocity, 1 pressure) of @p from, the
      /// locally owned entries, on the kernels' layout (no ghost values).
      void
      copy_to_kernel_layout(const TrilinosWrappers::MPI::BlockVector &from,
                            const unsigned int                        block,
                            VectorType                               &to) const
      {
        matrix_free->initialize_dof_vector(to, block);
        const Utilities::MPI::Partitioner &partitioner =
          *matrix_free->get_vector_partitioner(block);
        for (unsigned int i = 0; i < partitioner.locally_owned_size(); ++i)
          to.local_element(i) = from.block(block)(partitioner.local_to_global(i));
      }
    };
  } // namespace fluid
} // namespace softsand

#endif
