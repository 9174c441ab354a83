#include <softsand/base/warnings.h>
#include <softsand/postprocess/columns/flow_regime_columns.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <sstream>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    FlowRegimeColumns<dim>::FlowRegimeColumns(const double       density,
                                              const double       viscosity,
                                              const std::string &creeping_model,
                                              const std::string &inertial_model)
      : density(density)
      , viscosity(viscosity)
      , creeping_model(creeping_model)
      , inertial_model(inertial_model)
    {}


    template <int dim>
    void
    FlowRegimeColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                        Columns                  &row) const
    {
      if (s.grains.empty())
        return;
      const double diameter = dem::mean_diameter(s.grains);
      const auto re = compute_pore_reynolds(s.fluid.get_dof_handler(),
                                            s.fluid.get_solution(),
                                            s.solid_field,
                                            density,
                                            viscosity,
                                            diameter);
      row["pore_reynolds_max"] = re.max;
      row["pore_reynolds_p95"] = re.p95;

      // The 95th percentile: a few cells at an inlet or a throat do not
      // make the scene inertial, 5 % of its pore volume does.
      if (!creeping_model.empty() && re.p95 > 1)
        {
          std::ostringstream message;
          message.precision(3);
          message
            << creeping_model << " neglects the fluid's inertia, valid for "
            << "pore Reynolds numbers rho |u| d / mu << 1; at step " << s.step
            << " (t = " << s.time << " s) 5 % of the pore volume has Re_p > "
            << re.p95 << " (largest " << re.max << ", d = " << diameter
            << " m, the grains' mean diameter): the pressure drop and the "
            << "forces on the grains miss the inertial (Ergun, Forchheimer) "
            << "part. Use " << inertial_model
            << ", or lower the driving pressure or flow rate. Given once; the "
            << "columns pore_reynolds_max and pore_reynolds_p95 follow it.";
          base::warn_once("creeping flow above Re_p 1",
                          message.str(),
                          s.triangulation.get_communicator());
        }
    }

    template class FlowRegimeColumns<2>;
    template class FlowRegimeColumns<3>;
  } // namespace postprocess
} // namespace softsand
