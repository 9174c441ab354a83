#ifndef softsand_postprocess_columns_radial_flow_columns_h
#define softsand_postprocess_columns_radial_flow_columns_h

#include <softsand/fluid/pressure_region.h>
#include <softsand/postprocess/columns/fluid_column_source.h>
#include <softsand/postprocess/radial_flow.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Radial cells (the Hele-Shaw injection, the paper's section 4): the
     * mean pressure on rings around the inlet, the radial flow rate and the
     * radial Darcy permeability between rings and over all of them; the
     * superficial velocity Q / (2 pi r h) at the innermost ring and its pore
     * Reynolds number rho q d / mu (d the grains' mean diameter).
     */
    template <int dim>
    class RadialFlowColumns : public FluidColumnSource<dim>
    {
    public:
      /// @p thickness: the layer between the plates (1 in 2D).
      RadialFlowColumns(const RadialFlowParameters          &parameters,
                        const fluid::PressureRegion<dim> &inlet,
                        const double                      thickness,
                        const double                      density,
                        const double                      viscosity);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const RadialFlowParameters       parameters;
      const fluid::PressureRegion<dim> inlet;
      const double                     thickness, density, viscosity;
    };
  } // namespace postprocess
} // namespace softsand

#endif
