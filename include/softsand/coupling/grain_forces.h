#ifndef softsand_coupling_grain_forces_h
#define softsand_coupling_grain_forces_h

#include <softsand/coupling/grain_solid_field.h>
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

    /**
     * The hybrid model's force on grains in the porous zone, added to
     * @p forces (doc/architecture.md, "The hybrid model"). Per unit volume
     * of pack the fluid pushes the grains by -(1 - phi) grad p and drags
     * them by phi c (u - phi v) (c the porous cell's drag coefficient, u the
     * superficial velocity, v the grain's velocity), so one grain of volume
     * V feels F = V (-grad p + phi c (u - phi v) / (1 - phi)); at rest
     * (u = -grad p / c) that is -V grad p / (1 - phi). A grain beyond the
     * zone's surface by a share s of its volume gets s F, evaluated at the
     * middle of that share; its rigid nodes carry the rest. No torque.
     */
    template <int dim>
    void
    add_porous_grain_forces(const fluid::PenalizedNavierStokes<dim> &fluid,
                            const std::vector<dem::Grain<dim>>      &grains,
                            const GrainSolidField<dim>              &solids,
                            const double                   viscosity,
                            const double                   density,
                            GrainForces<dim>              &forces,
                            const MPI_Comm                 comm);
  } // namespace coupling
} // namespace softsand

#endif
