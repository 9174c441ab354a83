#ifndef softsand_postprocess_columns_porosity_columns_h
#define softsand_postprocess_columns_porosity_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Resolution and porosity of a scene with grains: cells per smallest
     * diameter, the paper's fluid-cell porosity and the void-fraction
     * integral, over the box and (with two pressure planes) between the
     * planes where K is measured. No columns once the grains are gone.
     */
    template <int dim>
    class PorosityColumns : public FluidColumnSource<dim>
    {
    public:
      PorosityColumns(const unsigned int         flow_axis,
                      const std::vector<double> &pressure_planes);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const unsigned int        flow_axis;
      const std::vector<double> pressure_planes;
    };
  } // namespace postprocess
} // namespace softsand

#endif
