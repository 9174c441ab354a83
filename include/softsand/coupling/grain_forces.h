#ifndef softsand_coupling_grain_forces_h
#define softsand_coupling_grain_forces_h

#include <softsand/dem/grain.h>
#include <softsand/fluid/penalized_navier_stokes.h>

#include <vector>

namespace softsand
{
  namespace coupling
  {
    using namespace dealii;

    /// Fluid force and torque on each grain (summed over all ranks).
    template <int dim>
    struct GrainForces
    {
      std::vector<Tensor<1, dim>> force;
      std::vector<Tensor<1, 3>>   torque;

      Tensor<1, dim>
      total_force() const;
    };

    enum class ForceModel
    {
      /// Integral of the penalization reaction over the grain: the exact
      /// discrete force (it balances the boundary tractions).
      penalization_reaction,
      /// The paper's Eq. (7), mu lap u - grad p integrated over the grain's
      /// cells: misses the stress jumps across faces; a diagnostic only.
      stress_divergence
    };

    template <int dim>
    GrainForces<dim>
    compute_grain_forces(const fluid::PenalizedNavierStokes<dim> &fluid,
                         const std::vector<dem::Grain<dim>>      &grains,
                         const ForceModel                          model,
                         const MPI_Comm                            comm);
  } // namespace coupling
} // namespace softsand

#endif
