#include <deal.II/base/function_parser.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/columns/error_columns.h>
#include <softsand/postprocess/flow_diagnostics.h>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    ErrorColumns<dim>::ErrorColumns(const std::string &exact_velocity,
                                    const std::string &exact_pressure)
      : expression(exact_velocity + ";" +
                   (exact_pressure.empty() ? std::string("0") : exact_pressure))
    {}


    template <int dim>
    void
    ErrorColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                   Columns                  &row) const
    {
      FunctionParser<dim> exact(dim + 1);
      exact.initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                       expression,
                       base::function_constants(),
                       true);
      exact.set_time(s.time);
      const auto e = compute_errors(s.fluid.get_dof_handler(),
                                    s.fluid.get_solution(),
                                    exact);
      row["velocity_l2_error"] = e.velocity_l2;
      row["velocity_h1_error"] = e.velocity_h1_semi;
      row["pressure_l2_error"] = e.pressure_l2;
    }

    template class ErrorColumns<2>;
    template class ErrorColumns<3>;
  } // namespace postprocess
} // namespace softsand
