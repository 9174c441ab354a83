#ifndef softsand_io_grain_output_h
#define softsand_io_grain_output_h

#include <deal.II/particles/particle_handler.h>

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

      void
      write(const Particles::ParticleHandler<3> &particles,
            const double                         time,
            const MPI_Comm                       comm);

    private:
      std::string                                 directory;
      std::string                                 base_name;
      unsigned int                                counter = 0;
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace io
} // namespace softsand

#endif
