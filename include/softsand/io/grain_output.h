#ifndef softsand_io_grain_output_h
#define softsand_io_grain_output_h

#include <deal.II/particles/particle_handler.h>

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
     * Grains for ParaView: Particles::DataOut points (VTU per rank, PVTU per
     * step, PVD series rewritten atomically) with radius, velocity, angular
     * velocity, force, torque, fluid force and number of contacts.
     */
    class GrainOutput
    {
    public:
      GrainOutput(const std::string &directory, const std::string &base_name);

      /// A restarted run continues the series of the run it resumes at
      /// @p time (see PvdSeries::resume()).
      void
      resume(const double time)
      {
        series.resume(time);
      }

      /// The grains at @p time, the state after step @p step (0: the
      /// initial state), in BASE_NNNNN.pvtu (see PvdSeries::file_number()).
      void
      write(const Particles::ParticleHandler<3> &particles,
            const double                         time,
            const unsigned long                  step,
            const MPI_Comm                       comm);

    private:
      PvdSeries series;
    };
  } // namespace io
} // namespace softsand

#endif
