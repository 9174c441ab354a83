#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/postprocess/columns/radial_flow_columns.h>

#include <cmath>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    RadialFlowColumns<dim>::RadialFlowColumns(
      const RadialFlowParameters       &parameters,
      const fluid::PressureRegion<dim> &inlet,
      const double                      thickness,
      const double                      density,
      const double                      viscosity)
      : parameters(parameters)
      , inlet(inlet)
      , thickness(thickness)
      , density(density)
      , viscosity(viscosity)
    {}


    template <int dim>
    void
    RadialFlowColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                        Columns                  &row) const
    {
      const auto  &radii      = parameters.radii;
      const double half_width = parameters.ring_half_width > 0 ?
                                  parameters.ring_half_width :
                                  0.5 * coupling::min_cell_edge(s.triangulation);
      const auto   flow       = compute_radial_flow(s.fluid.get_dof_handler(),
                                              s.fluid.get_solution(),
                                              s.grains.empty() ? nullptr :
                                                                 &s.solid_field,
                                              inlet,
                                              radii,
                                              half_width,
                                              s.pores);
      for (unsigned int k = 0; k < radii.size(); ++k)
        {
          row["ring_pressure_" + std::to_string(k)] = flow.ring_pressure[k];
          if (k + 1 < radii.size())
            row["radial_permeability_" + std::to_string(k)] =
              flow.permeability(
                radii, k, k + 1, flow.flow_rate[k], viscosity, thickness);
        }
      row["radial_flow_rate"]    = flow.total_flow_rate;
      row["radial_permeability"] = flow.permeability(radii,
                                                     0,
                                                     radii.size() - 1,
                                                     flow.total_flow_rate,
                                                     viscosity,
                                                     thickness);
      // The ring's circumference (dim = 2: the flow rate is per unit depth).
      const double superficial_velocity =
        flow.total_flow_rate / (2 * numbers::PI * radii.front() * thickness);
      row["radial_superficial_velocity"] = superficial_velocity;
      if (!s.grains.empty())
        row["radial_pore_reynolds"] = density * std::abs(superficial_velocity) *
                                      dem::mean_diameter(s.grains) / viscosity;
    }

    template class RadialFlowColumns<2>;
    template class RadialFlowColumns<3>;
  } // namespace postprocess
} // namespace softsand
