#ifndef softsand_postprocess_columns_force_columns_h
#define softsand_postprocess_columns_force_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Fluid forces: the total on the grains (discrete reaction and Eq. 7),
     * on the box faces along the flow axis (traction integral and discrete
     * reaction: with the grains' they close the momentum balance), and the
     * first grain's drag coefficient, Stokes ratio and Reynolds number
     * against a reference velocity (none when it is zero).
     */
    template <int dim>
    class ForceColumns : public FluidColumnSource<dim>
    {
    public:
      ForceColumns(const unsigned int flow_axis,
                   const double       viscosity,
                   const double       density,
                   const double       reference_velocity);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const unsigned int flow_axis;
      const double       viscosity, density, reference_velocity;
    };
  } // namespace postprocess
} // namespace softsand

#endif
