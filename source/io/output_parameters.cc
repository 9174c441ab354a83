#include <softsand/io/output_parameters.h>

namespace softsand
{
  namespace io
  {
    void
    OutputParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("output");
      prm.declare_entry("directory",
                        "output",
                        Patterns::DirectoryName(),
                        "Output directory (created if missing): "
                        "statistics.txt, VTU/PVTU/PVD, grain_forces.txt.");
      prm.declare_entry("write vtu",
                        "true",
                        Patterns::Bool(),
                        "Write fluid fields for ParaView.");
      prm.declare_entry("output interval",
                        "1",
                        Patterns::Integer(1),
                        "Transient runs: write fields every this many "
                        "steps (and at the last step).");
      prm.declare_entry("verbosity",
                        "normal",
                        Patterns::Selection("quiet|normal|verbose"),
                        "What the screen shows. quiet: only the final results "
                        "(log.txt in the output directory still gets the "
                        "progress and timing); normal: progress and timing; "
                        "verbose: also nonlinear iterations.");
      prm.leave_subsection();
    }


    void
    OutputParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("output");
      directory       = prm.get("directory");
      write_vtu       = prm.get_bool("write vtu");
      output_interval = prm.get_integer("output interval");
      const std::string v = prm.get("verbosity");
      verbosity = v == "quiet"  ? Verbosity::quiet :
                  v == "normal" ? Verbosity::normal :
                                  Verbosity::verbose;
      prm.leave_subsection();
    }
  } // namespace io
} // namespace softsand
