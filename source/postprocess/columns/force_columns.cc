#include <softsand/postprocess/columns/force_columns.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <cmath>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    ForceColumns<dim>::ForceColumns(const unsigned int flow_axis,
                                    const double       viscosity,
                                    const double       density,
                                    const double       reference_velocity)
      : flow_axis(flow_axis)
      , viscosity(viscosity)
      , density(density)
      , reference_velocity(reference_velocity)
    {}


    template <int dim>
    void
    ForceColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                   Columns                  &row) const
    {
      const char           names[3]  = {'x', 'y', 'z'};
      const std::string    axis_name(1, names[flow_axis]);
      const Tensor<1, dim> total     = s.forces.total_force();
      const Tensor<1, dim> total_eq7 = s.forces_eq7.total_force();
      // The Eq. 7 forces only when they were computed (on request).
      const bool eq7 = !s.forces_eq7.force.empty();
      for (unsigned int d = 0; d < dim; ++d)
        {
          row[std::string("grain_force_") + names[d]] = total[d];
          if (eq7)
            row[std::string("eq7_grain_force_") + names[d]] = total_eq7[d];
        }
      row["boundary_force_" + axis_name] =
        boundary_traction(s.fluid.get_dof_handler(),
                          s.fluid.get_solution(),
                          viscosity)[flow_axis];
      // The discrete momentum balance: fluid force on grains + on the box
      // faces + body force = 0 (steady).
      row["boundary_reaction_" + axis_name] =
        s.fluid.boundary_force()[flow_axis];

      // Drag coefficient and Stokes ratio of the first grain.
      const double U = reference_velocity;
      if (s.grains.empty() || U <= 0)
        return;
      const double d    = s.grains[0].diameter();
      const double area = (dim == 3) ? M_PI * d * d / 4 : d;
      const double F    = s.forces.force[0][flow_axis];
      row["drag_coefficient"] = 2 * F / (density * U * U * area);
      if (dim == 3)
        {
          row["stokes_drag_ratio"] = F / (3 * M_PI * viscosity * d * U);
          if (eq7)
            row["eq7_stokes_drag_ratio"] =
            s.forces_eq7.force[0][flow_axis] / (3 * M_PI * viscosity * d * U);
        }
      row["reynolds_number"] = density * U * d / viscosity;
    }

    template class ForceColumns<2>;
    template class ForceColumns<3>;
  } // namespace postprocess
} // namespace softsand
