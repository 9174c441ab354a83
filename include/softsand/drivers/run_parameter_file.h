#ifndef softsand_drivers_run_parameter_file_h
#define softsand_drivers_run_parameter_file_h

#include <deal.II/base/mpi.h>

#include <string>

namespace softsand
{
  namespace drivers
  {
    /// Reads @p filename and runs it in its dimension: a convergence study
    /// when it names a knob, else its scene (run_scene()).
    void
    run_parameter_file(const std::string &filename, const MPI_Comm comm);
  } // namespace drivers
} // namespace softsand

#endif
