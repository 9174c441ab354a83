#ifndef softsand_io_pvd_series_h
#define softsand_io_pvd_series_h

#include <deal.II/base/mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace io
  {
    /**
     * The PVD time series of one kind of output (fields, grains, walls):
     * the number of the next step's files and the list of their records,
     * rewritten atomically (temporary file + rename) after each step, so
     * that a viewer never sees a reference to a partial step. A restarted
     * run resumes the series of the run it continues instead of numbering
     * from 0 again and overwriting its files.
     */
    class PvdSeries
    {
    public:
      PvdSeries(const std::string &directory, const std::string &base_name);

      /// Continue the series in the directory's BASE.pvd: its records up to
      /// @p time are kept, the numbering continues after the last of them.
      /// Every rank reads the file.
      void
      resume(const double time);

      /// The number of the next step's files.
      unsigned int
      next_number() const
      {
        return counter;
      }

      /// The step's record file @p file (relative to the directory) at
      /// @p time; rank 0 rewrites the .pvd.
      void
      add(const double time, const std::string &file, const MPI_Comm comm);

    private:
      std::string                                 directory;
      std::string                                 base_name;
      unsigned int                                counter = 0;
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace io
} // namespace softsand

#endif
