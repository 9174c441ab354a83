#ifndef softsand_postprocess_columns_permeability_columns_h
#define softsand_postprocess_columns_permeability_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Pressure drop along the flow axis (between two planes, fluid-weighted
     * slab means, or between the inflow and outflow faces), the flow rate
     * through the inflow face, the superficial velocity q and Darcy's
     * permeability K = q mu L / dp.
     */
    template <int dim>
    class PermeabilityColumns : public FluidColumnSource<dim>
    {
    public:
      /// @p pressure_planes: none (the box faces) or two positions on the
      /// axis; @p box_length: the domain along the axis. The superficial
      /// velocity divides the flow rate by the inflow face's meshed area.
      PermeabilityColumns(const unsigned int         flow_axis,
                          const double               viscosity,
                          const std::vector<double> &pressure_planes,
                          const double               box_length);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const unsigned int        flow_axis;
      const double              viscosity;
      const std::vector<double> pressure_planes;
      const double              box_length;
    };
  } // namespace postprocess
} // namespace softsand

#endif
