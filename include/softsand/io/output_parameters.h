#ifndef softsand_io_output_parameters_h
#define softsand_io_output_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    /// Where and what a run writes.
    struct OutputParameters
    {
      std::string  directory      = "output";
      bool         write_vtu      = true;
      unsigned int output_interval = 1;
      /// quiet: only the final results (deterministic, for tests); normal:
      /// progress and timing; verbose: also solver details.
      enum class Verbosity
      {
        quiet,
        normal,
        verbose
      };
      Verbosity verbosity = Verbosity::normal;

      /// Whether the fields of time step @p step are written: every output
      /// interval and at the last step.
      bool
      output_due(const unsigned int step, const bool last) const
      {
        return last || (output_interval > 0 && step % output_interval == 0);
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace io
} // namespace softsand

#endif
