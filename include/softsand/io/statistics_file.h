#ifndef softsand_io_statistics_file_h
#define softsand_io_statistics_file_h

#include <deal.II/base/mpi.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace io
  {
    /**
     * The statistics table of a run: whitespace-separated columns, a first
     * line "# name1 name2 ...", one row per step or solve, flushed at every
     * row so that nothing is lost if a long run stops. Rank 0 writes.
     */
    class StatisticsFile
    {
    public:
      StatisticsFile(const std::string &filename, const MPI_Comm comm);

      /// Set a column of the current row (the first row fixes the columns).
      void
      add_value(const std::string &column, const double value);

      /// Write the current row (and the header before the first row).
      void
      write_row();

    private:
      bool                                      is_writer;
      std::string                               filename;
      std::ofstream                             file;
      std::vector<std::string>                  columns;
      std::vector<std::pair<std::string, double>> row;
    };
  } // namespace io
} // namespace softsand

#endif
