#ifndef softsand_postprocess_radial_flow_h
#define softsand_postprocess_radial_flow_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <softsand/fluid/pressure_region.h>
#include <softsand/fluid/solid_field.h>

#include <softsand/postprocess/pore_connectivity.h>

#include <vector>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * Subsection "postprocessing/radial flow": pressure rings and flow rates
     * around the inlet of a radial cell (Hele-Shaw), and the Darcy
     * permeability of the pack between the rings.
     */
    struct RadialFlowParameters
    {
      /// Ring radii around the inlet axis, ascending (m); empty: off.
      std::vector<double> radii;
      /// Half width of a pressure ring (m); 0: half the finest cell.
      double ring_half_width = 0;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };


    /// Radial flow around an axis (3D) or a centre (2D).
    struct RadialFlow
    {
      /// Fluid-averaged pressure on each ring (Pa).
      std::vector<double> ring_pressure;
      /// Outward flow rate through the cylinder between consecutive rings,
      /// int u . e_r dV / (r_{k+1} - r_k) over the annulus (m^3/s; 2D:
      /// m^2/s).
      std::vector<double> flow_rate;
      /// Over the whole range of rings.
      double total_flow_rate = 0;

      /**
       * Darcy permeability of the annulus between rings @p k and @p l for a
       * layer of thickness @p thickness (3D; ignored in 2D): radial Darcy
       * flow Q = 2 pi h K (p_k - p_l) / (mu ln(r_l / r_k)), so
       * K = Q mu ln(r_l / r_k) / (2 pi h (p_k - p_l)) (m^2).
       */
      double
      permeability(const std::vector<double> &radii,
                   const unsigned int         k,
                   const unsigned int         l,
                   const double               flow_rate,
                   const double               viscosity,
                   const double               thickness) const;
    };


    /**
     * Ring pressures and flow rates of @p solution around the axis of
     * @p axis_region (its centre and axis; usually the inlet). The ring
     * pressure is the mean over the fluid (weighted by the void fraction of
     * @p solids, if given) within @p half_width of the radius, over the
     * connected pore space of @p pores if given (sealed pockets float; a
     * ring that meets no connected cell takes all its fluid); the flow
     * rate through radius r is int u . e_r dA, here averaged over the
     * annulus between two rings as a volume integral (grains included:
     * they carry their own velocity).
     */
    template <int dim>
    RadialFlow
    compute_radial_flow(const DoFHandler<dim>                        &dof_handler,
                        const TrilinosWrappers::MPI::BlockVector     &solution,
                        const fluid::SolidField<dim>                 *solids,
                        const fluid::PressureRegion<dim>             &axis_region,
                        const std::vector<double>                    &radii,
                        const double                                  half_width,
                        const PoreConnectivity *pores = nullptr);
  } // namespace postprocess
} // namespace softsand

#endif
