#ifndef softsand_coupling_coupling_parameters_h
#define softsand_coupling_coupling_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace softsand
{
  namespace coupling
  {
    using namespace dealii;

    /**
     * Subsection "coupling": how the grains of the DEM and the fluid exchange
     * velocity and force in a coupled run (simulation control/mode =
     * coupled); doc/architecture.md, "One coupled step".
     */
    struct CouplingParameters
    {
      enum class FluidModel
      {
        /// The paper: BDF time marching of the penalized Navier-Stokes
        /// equations, one fluid step per coupling step.
        transient,
        /// Creeping flow: one steady Stokes-Brinkman solve per coupling
        /// step with the grains' current velocities; the step is set by how
        /// far the grains move.
        quasi_steady
      };
      FluidModel fluid_model = FluidModel::transient;

      /// Re-adapt the mesh once a grain moved this fraction of the finest
      /// cell edge since the last adaptation; cells within that distance of
      /// a grain surface are kept fine.
      double readapt_fraction = 0.5;

      /// Quasi-steady: the coupling step lets the fastest grain move at
      /// most this fraction of the finest cell edge (capped by simulation
      /// control/time step).
      double max_displacement_fraction = 0.25;

      /// Transient: the coupling step is simulation control/time step
      /// halved until the largest cell Courant number is at most this (0:
      /// fixed steps).
      double max_courant_number = 0;

      /// Transient: the coupling step is also halved until the relative
      /// change of the velocity per step, predicted from the last step's,
      /// is at most this (0: off).
      double max_velocity_change = 0;

      /// DEM sub-steps per coupling step (0: as many as the DEM's stable
      /// step needs).
      unsigned int dem_substeps = 0;

      /// Added-mass coefficient C of the held force's response to a change
      /// of a grain's velocity during the sub-steps: K = C rho_f V / dt +
      /// 3 pi mu d (see dem::GranularDynamics::set_fluid_forces()).
      double added_mass_coefficient = 0.5;

      /// Add the hydrostatic (buoyancy) force -rho_f V g on each grain: the
      /// fluid is solved for the pressure without its hydrostatic part.
      bool buoyancy = true;

      /// Grain force from the penalization reaction (exact discrete force)
      /// or the paper's Eq. (7).
      bool paper_force = false;

      /// Load-balancing weight of a cell cut by a grain surface, in plain
      /// cells (assembly evaluates the grains at its quadrature points).
      double cut_cell_weight = 3;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace coupling
} // namespace softsand

#endif
