#ifndef softsand_io_pvd_series_h
#define softsand_io_pvd_series_h

#include <deal.II/base/data_out_base.h>
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
     * the list of its records, rewritten atomically (temporary file +
     * rename) after each step, so that a viewer never sees a reference to
     * a partial step. Every series names its files by the step they belong
     * to (step 0 the initial state; see file_number()), so a restarted run
     * that resumes the series writes the steps after its checkpoint under
     * their own names and never overwrites another step's files.
     */
    class PvdSeries
    {
    public:
      PvdSeries(const std::string &directory, const std::string &base_name);

      /// Continue the series in the directory's BASE.pvd: its records up to
      /// @p time are kept. Every rank reads the file.
      void
      resume(const double time);

      /// The step's record file @p file (relative to the directory) at
      /// @p time; rank 0 rewrites the .pvd. A second record of the same
      /// file (a step written again at the run's end) replaces the first.
      void
      add(const double time, const std::string &file, const MPI_Comm comm);

      /// Step @p step of a deal.II DataOut (fields, particles) at @p time:
      /// BASE_NNNNN.pvtu with a .vtu piece per rank, and its record.
      template <int dim, int spacedim>
      void
      write_step(const dealii::DataOutInterface<dim, spacedim> &data_out,
                 const unsigned long                            step,
                 const double                                   time,
                 const MPI_Comm                                 comm)
      {
        add(time,
            data_out.write_vtu_with_pvtu_record(
              directory + "/", base_name, step, comm, n_digits(step), 0),
            comm);
      }

      /// The digits of the number in the files of step @p step: five, more
      /// when the step needs them (DEM steps).
      static unsigned int
      n_digits(const unsigned long step);

      /// The number in the name of the files of step @p step, e.g.
      /// "00012".
      static std::string
      file_number(const unsigned long step);

    private:
      std::string                                 directory;
      std::string                                 base_name;
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace io
} // namespace softsand

#endif
