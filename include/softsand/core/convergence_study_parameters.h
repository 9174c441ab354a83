#ifndef softsand_core_convergence_study_parameters_h
#define softsand_core_convergence_study_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace core
  {
    using namespace dealii;

    /**
     * Subsection "convergence study": one discretization knob and the values
     * it takes. A scene with a knob other than 'none' is run once per value
     * and a convergence table of one statistics column (drag, permeability,
     * pressure drop, ...) is written instead of a single run's results.
     */
    struct ConvergenceStudyParameters
    {
      enum class Knob
      {
        none,
        cells_per_diameter,
        global_refinements,
        theta,
        time_step
      };
      Knob                knob = Knob::none;
      std::vector<double> values;
      /// A column of the statistics table (its last row is used).
      std::string quantity = "drag_coefficient";
      /// Known exact value of the quantity (has_reference: one was given).
      bool   has_reference   = false;
      double reference_value = 0;
      /// Order assumed by the Richardson estimate (0: the observed order).
      double richardson_order = 0;
      /// Base name of the table files in the output directory.
      std::string table_name = "convergence";

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// The knob's name as in the .prm and as the table's first column.
      std::string
      knob_name() const;
    };
  } // namespace core
} // namespace softsand

#endif
