#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/postprocess/columns/porosity_columns.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <algorithm>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    PorosityColumns<dim>::PorosityColumns(
      const unsigned int         flow_axis,
      const std::vector<double> &pressure_planes)
      : flow_axis(flow_axis)
      , pressure_planes(pressure_planes)
    {}


    template <int dim>
    void
    PorosityColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                      Columns                  &row) const
    {
      if (s.grains.empty())
        return;
      row["cells_per_diameter"] = s.solid_field.locator().min_diameter() /
                                  coupling::min_cell_edge(s.triangulation);
      const auto porosity = compute_porosity(s.triangulation, s.solid_field);
      row["porosity_cells"]    = porosity.fluid_cell_fraction;
      row["porosity_integral"] = porosity.void_fraction_integral;
      if (pressure_planes.size() == 2)
        {
          // Between the planes where K is measured, away from buffers.
          const auto slab =
            compute_porosity(s.triangulation,
                             s.solid_field,
                             flow_axis,
                             std::min(pressure_planes[0], pressure_planes[1]),
                             std::max(pressure_planes[0], pressure_planes[1]));
          row["slab_porosity_cells"]    = slab.fluid_cell_fraction;
          row["slab_porosity_integral"] = slab.void_fraction_integral;
        }
    }

    template class PorosityColumns<2>;
    template class PorosityColumns<3>;
  } // namespace postprocess
} // namespace softsand
