#include <softsand/fluid/block_schur_preconditioner.h>

#include <deal.II/lac/solver_cg.h>

#include <EpetraExt_MatrixMatrix.h>

namespace softsand
{
  namespace fluid
  {
    namespace
    {
      /// B diag(A)^-1 B^T of the assembled saddle-point matrix, with a
      /// regular diagonal on every row.
      void
      build_discrete_brinkman(
        const TrilinosWrappers::BlockSparseMatrix &system_matrix,
        TrilinosWrappers::SparseMatrix            &discrete_brinkman)
      {
        const auto                   &a = system_matrix.block(0, 0);
        TrilinosWrappers::MPI::Vector inverse(a.locally_owned_domain_indices(),
                                              a.get_mpi_communicator());
        for (const auto i : inverse.locally_owned_elements())
          {
            const double d = a.diag_element(i);
            inverse(i)     = d > 0 ? 1. / d : 0.;
          }
        inverse.compress(VectorOperation::insert);
        // The divergence rows times D^-1 times the gradient columns (the
        // blocks carry the same sign).
        TrilinosWrappers::SparseMatrix product;
        system_matrix.block(1, 0).mmult(product,
                                        system_matrix.block(0, 1),
                                        inverse);
        // Constrained (hanging) pressure nodes have empty B rows: add the
        // pressure block, which holds their constraint diagonal, then give
        // zero diagonals the mean, so that AMG and CG see a regular matrix
        // (these values are overwritten by the constraints).
        {
          Epetra_CrsMatrix *sum  = nullptr;
          const int         ierr = EpetraExt::MatrixMatrix::Add(
            product.trilinos_matrix(),
            false,
            1.,
            system_matrix.block(1, 1).trilinos_matrix(),
            false,
            1.,
            sum);
          AssertThrow(ierr == 0 && sum != nullptr,
                      ExcMessage("EpetraExt could not add the pressure block "
                                 "to B D^-1 B^T."));
          sum->FillComplete(product.trilinos_matrix().DomainMap(),
                            product.trilinos_matrix().RangeMap());
          discrete_brinkman.reinit(*sum);
          delete sum;
        }
        double     sum = 0, count = 0;
        const auto range = discrete_brinkman.local_range();
        for (auto i = range.first; i < range.second; ++i)
          if (discrete_brinkman.diag_element(i) > 0)
            {
              sum += discrete_brinkman.diag_element(i);
              ++count;
            }
        const MPI_Comm comm = discrete_brinkman.get_mpi_communicator();
        const double   mean = Utilities::MPI::sum(sum, comm) /
                            std::max(1., Utilities::MPI::sum(count, comm));
        for (auto i = range.first; i < range.second; ++i)
          if (!(discrete_brinkman.diag_element(i) > 0))
            discrete_brinkman.set(i, i, mean);
        discrete_brinkman.compress(VectorOperation::insert);
      }
    } // namespace


    TrilinosWrappers::PreconditionAMG::AdditionalData
    pressure_laplace_amg_data()
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      return data;
    }


    BlockSchurPreconditioner::BlockSchurPreconditioner(
      const TrilinosWrappers::BlockSparseMatrix &system_matrix,
      const TrilinosWrappers::BlockSparseMatrix &pressure_mass_matrix,
      const TrilinosWrappers::BlockSparseMatrix *pressure_laplace_matrix,
      const std::vector<std::vector<bool>>      &velocity_constant_modes,
      const bool                                 convection,
      const unsigned int                         amg_sweeps,
      const std::string                         &velocity_smoother,
      const bool                                 discrete_brinkman_schur,
      const double                               inner_tolerance)
      : system_matrix(system_matrix)
      , velocity_smoother(velocity_smoother)
      , use_laplace(pressure_laplace_matrix != nullptr ||
                    discrete_brinkman_schur)
      , inner_tolerance(inner_tolerance)
    {
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.constant_modes        = velocity_constant_modes;
        data.elliptic              = true;
        data.higher_order_elements = true;
        data.smoother_sweeps       = amg_sweeps;
        data.aggregation_threshold = 0.02;
        data.smoother_type         = this->velocity_smoother.c_str();
        velocity_amg.initialize(system_matrix.block(0, 0), data);
      }
      pressure_mass_ilu.initialize(pressure_mass_matrix.block(1, 1));
      if (use_laplace)
        {
          const auto data = pressure_laplace_amg_data();
          if (discrete_brinkman_schur)
            {
              build_discrete_brinkman(system_matrix, discrete_brinkman);
              pressure_laplace_amg.initialize(discrete_brinkman, data);
            }
          else
            pressure_laplace_amg.initialize(pressure_laplace_matrix->block(1, 1),
                                            data);
        }
      tmp_u.reinit(system_matrix.block(0, 0).locally_owned_range_indices(),
                   system_matrix.get_mpi_communicator());
      tmp_p.reinit(system_matrix.block(1, 1).locally_owned_range_indices(),
                   system_matrix.get_mpi_communicator());
    }


    void
    BlockSchurPreconditioner::vmult(BlockVector &dst, const BlockVector &src) const
    {
      // Pressure: dst_p = -S^-1 src_p.
      pressure_mass_ilu.vmult(dst.block(1), src.block(1));
      if (use_laplace)
        {
          if (discrete_brinkman.m() > 0)
            {
              // A preconditioner may be inexact (FGMRES): an inner solve
              // that stops at its bound (nearly closed pores make B D^-1 B^T
              // nearly singular) still returns its last iterate.
              ReductionControl control(
                200, 1e-300, inner_tolerance, false, false);
              SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
              tmp_p = 0;
              try
                {
                  cg.solve(discrete_brinkman, tmp_p, src.block(1),
                           pressure_laplace_amg);
                }
              catch (const SolverControl::NoConvergence &)
                {}
            }
          else
            pressure_laplace_amg.vmult(tmp_p, src.block(1));
          dst.block(1) += tmp_p;
        }
      dst.block(1) *= -1.;
      // Velocity: dst_u = A^-1 (src_u - B^T dst_p).
      system_matrix.block(0, 1).vmult(tmp_u, dst.block(1));
      tmp_u.sadd(-1., 1., src.block(0));
      velocity_amg.vmult(dst.block(0), tmp_u);
    }
  } // namespace fluid
} // namespace softsand
