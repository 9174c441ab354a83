#ifndef softsand_io_field_output_h
#define softsand_io_field_output_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/vector.h>

#include <softsand/io/pvd_series.h>

#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    /**
     * Fluid fields for ParaView: one VTU per rank and step, a PVTU per step
     * and a PVD time series. The PVD is rewritten atomically (temporary file
     * + rename) after the step's files are complete, so a viewer never sees
     * a reference to a partial step.
     */
    template <int dim>
    class FieldOutput
    {
    public:
      FieldOutput(const std::string &directory, const std::string &base_name);

      /// @p cell_void_fraction is indexed by active cell index.
      /// A restarted run continues the series of the run it resumes at
      /// @p time (see PvdSeries::resume()).
      void
      resume(const double time)
      {
        series.resume(time);
      }

      /// The fields at @p time, after step @p step (0: the initial state;
      /// a steady solve's cycle), in BASE_NNNNN.pvtu.
      void
      write(const DoFHandler<dim>                    &dof_handler,
            const TrilinosWrappers::MPI::BlockVector &solution,
            const Vector<float>                      &cell_void_fraction,
            const double                              time,
            const unsigned int                        step,
            const Vector<float> *pore_space = nullptr);

    private:
      PvdSeries series;
    };
  } // namespace io
} // namespace softsand

#endif
