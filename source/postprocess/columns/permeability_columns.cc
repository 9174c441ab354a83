#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/postprocess/columns/permeability_columns.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <cmath>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    PermeabilityColumns<dim>::PermeabilityColumns(
      const unsigned int         flow_axis,
      const double               viscosity,
      const std::vector<double> &pressure_planes,
      const double               box_length)
      : flow_axis(flow_axis)
      , viscosity(viscosity)
      , pressure_planes(pressure_planes)
      , box_length(box_length)
    {}


    template <int dim>
    void
    PermeabilityColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                          Columns                  &row) const
    {
      const auto        &dof  = s.fluid.get_dof_handler();
      const auto        &u    = s.fluid.get_solution();
      const unsigned int axis = flow_axis;
      double             dp = 0, length = 0;
      if (pressure_planes.size() == 2)
        {
          const double x1   = pressure_planes[0];
          const double x2   = pressure_planes[1];
          const double half = 0.5 * coupling::min_cell_edge(s.triangulation);
          dp = slab_mean_pressure(dof, u, &s.solid_field, axis, x1, half) -
               slab_mean_pressure(dof, u, &s.solid_field, axis, x2, half);
          length = std::abs(x2 - x1);
        }
      else
        {
          dp = boundary_mean_pressure(dof, u, 2 * axis) -
               boundary_mean_pressure(dof, u, 2 * axis + 1);
          length = box_length;
        }
      const double inflow        = -boundary_flux(dof, u, 2 * axis);
      const double q             = inflow / boundary_area(dof, 2 * axis);
      row["pressure_drop"]        = dp;
      row["flow_rate"]            = inflow;
      // The same through the opposite face: with no other opening, equal
      // to the inflow when the discrete flow conserves mass.
      row["outflow_rate"]         = boundary_flux(dof, u, 2 * axis + 1);
      row["superficial_velocity"] = q;
      row["permeability"]         = (dp != 0) ? q * viscosity * length / dp : 0.;
    }

    template class PermeabilityColumns<2>;
    template class PermeabilityColumns<3>;
  } // namespace postprocess
} // namespace softsand
