#ifndef softsand_tests_h
#define softsand_tests_h

// Minimal deal.II-style test support: everything written to deallog goes
// to the file "output", which the test driver compares with NAME.output.

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>

#include <fstream>
#include <iomanip>

using namespace dealii;

inline std::ofstream deallogfile;

/// Send deallog to "output" (not to the console) with fixed 6-digit
/// numbers, and without the job id line so that outputs compare. Under MPI
/// only rank 0 writes: tests print reduced, rank-independent results.
inline void
initlog()
{
  int initialized = 0;
  MPI_Initialized(&initialized);
  deallog.depth_console(0);
  if (initialized && Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;
  deallogfile.open("output");
  deallog.attach(deallogfile, false);
  deallog.precision(6);
  deallog.flags(std::ios::fixed | std::ios::showpoint | std::ios::left);
}

#endif
