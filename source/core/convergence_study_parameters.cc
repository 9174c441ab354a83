#include <softsand/base/parameter_tools.h>
#include <softsand/core/convergence_study_parameters.h>

namespace softsand
{
  namespace core
  {
    void
    ConvergenceStudyParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("convergence study");
      prm.declare_entry(
        "knob",
        "none",
        Patterns::Selection(
          "none|cells per diameter|global refinements|theta|time step"),
        "Run the scene once per value of this knob and write a convergence "
        "table instead of a single run (none: a single run). cells per "
        "diameter: mesh/cells per diameter (with mesh/refinement adaptive "
        "or uniform); global refinements: mesh/global refinements (scenes "
        "without grains, e.g. manufactured solutions); theta: fluid/theta; "
        "time step: simulation control/time step.");
      prm.declare_entry(
        "values",
        "",
        Patterns::List(Patterns::Double()),
        "Values of the knob, at least two, in any order (the table runs "
        "from coarse to fine): cells per diameter (dimensionless, 0 < N <= "
        "256), global refinements (integers 0..12), Theta (dimensionless, "
        "> 0) or time steps (s, > 0).");
      prm.declare_entry(
        "quantity",
        "drag_coefficient",
        Patterns::Anything(),
        "The quantity of interest: a column of the statistics table (its "
        "last row), e.g. drag_coefficient, stokes_drag_ratio, permeability "
        "(m^2), pressure_drop (Pa), grain_force_x (N), velocity_l2_error.");
      prm.declare_entry(
        "reference value",
        "",
        Patterns::Anything(),
        "Exact value of the quantity, in its units (empty: none). When "
        "given, the table adds the relative error against it and its "
        "order in DoFs.");
      prm.declare_entry(
        "richardson order",
        "0",
        Patterns::Double(0),
        "Order assumed in the Richardson estimate Q + (Q - Q_coarser) / "
        "(r^p - 1) (dimensionless; 0: the observed order of the last three "
        "runs, undefined where the changes alternate in sign).");
      prm.declare_entry("table name",
                        "convergence",
                        Patterns::FileName(),
                        "Base name of the tables written to the output "
                        "directory: NAME.txt (text), NAME.md (markdown) and "
                        "NAME.tex (LaTeX). Each run writes into the "
                        "subdirectory run-K of the output directory.");
      prm.leave_subsection();
    }


    void
    ConvergenceStudyParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("convergence study");
      const std::string k = prm.get("knob");
      knob = k == "cells per diameter" ? Knob::cells_per_diameter :
             k == "global refinements" ? Knob::global_refinements :
             k == "theta"              ? Knob::theta :
             k == "time step"          ? Knob::time_step :
                                         Knob::none;
      values.clear();
      const std::string text = prm.get("values");
      for (const auto &item : Utilities::split_string_list(text, ','))
        values.push_back(Utilities::string_to_double(item));
      quantity                    = prm.get("quantity");
      const std::string reference = prm.get("reference value");
      has_reference               = !reference.empty();
      if (has_reference)
        {
          try
            {
              reference_value = Utilities::string_to_double(reference);
            }
          catch (...)
            {
              base::throw_invalid_parameter("convergence study/reference value",
                                      reference,
                                      "a number or empty");
            }
          if (!std::isfinite(reference_value))
            base::throw_invalid_parameter("convergence study/reference value",
                                    reference,
                                    "a finite number or empty");
        }
      richardson_order = prm.get_double("richardson order");
      table_name       = prm.get("table name");
      if (table_name.empty() || table_name.find('/') != std::string::npos)
        base::throw_invalid_parameter("convergence study/table name",
                                table_name,
                                "a file name without '/'");
      if (knob != Knob::none)
        {
          if (values.size() < 2)
            base::throw_invalid_parameter("convergence study/values",
                                    text,
                                    "a study of '" + k +
                                      "' needs at least two values");
          for (const double v : values)
            {
              const std::string allowed =
                knob == Knob::cells_per_diameter ?
                  "cells per diameter must lie in (0, 256]" :
                knob == Knob::global_refinements ?
                  "global refinements must be integers from 0 to 12" :
                knob == Knob::theta ? "Theta must be finite and > 0" :
                                      "time steps must be finite and > 0 s";
              const bool ok = std::isfinite(v) &&
                              (knob == Knob::cells_per_diameter ?
                                 (v > 0 && v <= 256) :
                               knob == Knob::global_refinements ?
                                 (v >= 0 && v <= 12 && v == std::round(v)) :
                                 v > 0);
              if (!ok)
                base::throw_invalid_parameter("convergence study/values",
                                        text,
                                        allowed);
            }
          std::vector<double> sorted = values;
          std::sort(sorted.begin(), sorted.end());
          if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
            base::throw_invalid_parameter("convergence study/values",
                                    text,
                                    "the values must be distinct");
          if (quantity.empty())
            base::throw_invalid_parameter("convergence study/quantity",
                                    quantity,
                                    "a column name of the statistics table");
        }
      prm.leave_subsection();
    }


    std::string
    ConvergenceStudyParameters::knob_name() const
    {
      switch (knob)
        {
          case Knob::cells_per_diameter:
            return "cells per diameter";
          case Knob::global_refinements:
            return "global refinements";
          case Knob::theta:
            return "theta";
          case Knob::time_step:
            return "time step";
          default:
            return "none";
        }
    }
  } // namespace core
} // namespace softsand
