#include <softsand/fluid/block_schur_preconditioner.h>

namespace softsand
{
  namespace fluid
  {
    BlockSchurPreconditioner::BlockSchurPreconditioner(
      const TrilinosWrappers::BlockSparseMatrix &system_matrix,
      const TrilinosWrappers::BlockSparseMatrix &pressure_mass_matrix,
      const TrilinosWrappers::BlockSparseMatrix *pressure_laplace_matrix,
      const std::vector<std::vector<bool>>      &velocity_constant_modes,
      const bool                                 convection,
      const unsigned int                         amg_sweeps,
      const std::string                         &velocity_smoother)
      : system_matrix(system_matrix)
      , velocity_smoother(velocity_smoother)
      , use_laplace(pressure_laplace_matrix != nullptr)
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
          TrilinosWrappers::PreconditionAMG::AdditionalData data;
          data.elliptic              = true;
          data.higher_order_elements = false;
          data.smoother_sweeps       = 2;
          data.aggregation_threshold = 0.02;
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
