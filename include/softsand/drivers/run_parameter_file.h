#ifndef softsand_drivers_run_parameter_file_h
#define softsand_drivers_run_parameter_file_h

#include <deal.II/base/mpi.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace drivers
  {
    /// Reads @p filename, then the @p settings ("subsection/entry=value",
    /// the command line's --set options, checked as the file's lines), and
    /// runs it in its dimension: a convergence study when it names a knob,
    /// else its scene (run_scene()). A fresh run refuses an output
    /// directory that holds an earlier run's results.
    void
    run_parameter_file(const std::string              &filename,
                       const MPI_Comm                  comm,
                       const std::vector<std::string> &settings = {});
  } // namespace drivers
} // namespace softsand

#endif
