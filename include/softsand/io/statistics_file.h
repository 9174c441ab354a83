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
     * The statistics table of a run: a names line "step time wall_time
     * ...", then '#' lines, one per column with its unit ("# 3: wall_time
     * (s)"), then one row of whitespace-separated numbers per step or solve,
     * flushed at every row so that nothing is lost if a long run stops.
     * Rank 0 writes.
     */
    class StatisticsFile
    {
    public:
      /// A new table, or with @p resume_after_step >= 0 the existing one
      /// continued after its rows up to that step (a restarted run: rows the
      /// stopped run wrote after its checkpoint are dropped). The header
      /// names the units of a scene of dimension @p dim.
      StatisticsFile(const std::string &filename,
                     const MPI_Comm     comm,
                     const long         resume_after_step = new_file,
                     const unsigned int dim               = 3);

      static constexpr long new_file = -1;

      /// The column names of a statistics file read from its start: its
      /// names line, or for files of earlier versions the names in its
      /// only '#' line. Leaves @p in after the names.
      static std::vector<std::string>
      read_column_names(std::istream &in);

      /// Set a column of the current row (the first row fixes the columns).
      void
      add_value(const std::string &column, const double value);

      /// Write the current row (and the header before the first row).
      void
      write_row();

    private:
      bool                                      is_writer;
      std::string                               filename;
      unsigned int                              dim;
      std::ofstream                             file;
      std::vector<std::string>                  columns;
      std::vector<std::pair<std::string, double>> row;
    };
  } // namespace io
} // namespace softsand

#endif
