#include <deal.II/base/data_out_base.h>
#include <deal.II/particles/data_out.h>

#include <softsand/dem/granular_dynamics.h>
#include <softsand/io/grain_output.h>

#include <cstdio>
#include <fstream>

namespace softsand
{
  namespace io
  {
    GrainOutput::GrainOutput(const std::string &directory,
                             const std::string &base_name)
      : series(directory, base_name)
    {}


    void
    GrainOutput::write(const Particles::ParticleHandler<3> &particles,
                       const double                         time,
                       const unsigned long                  step,
                       const MPI_Comm                       comm)
    {
      using DCI = DataComponentInterpretation::DataComponentInterpretation;
      std::vector<std::string> names(dem::property::n_properties);
      std::vector<DCI> kinds(dem::property::n_properties,
                             DataComponentInterpretation::component_is_scalar);
      names[dem::property::radius]   = "radius";
      names[dem::property::density]  = "density";
      names[dem::property::contacts] = "contacts";
      names[dem::property::fluid_response] = "fluid_response";
      names[dem::property::fluid_rotational_response] =
        "fluid_rotational_response";
      const std::pair<unsigned int, const char *> vectors[] = {
        {dem::property::velocity, "velocity"},
        {dem::property::angular_velocity, "angular_velocity"},
        {dem::property::force, "force"},
        {dem::property::torque, "torque"},
        {dem::property::fluid_force, "fluid_force"},
        {dem::property::fluid_torque, "fluid_torque"},
        {dem::property::reference_velocity, "reference_velocity"},
        {dem::property::reference_angular_velocity,
         "reference_angular_velocity"}};
      for (const auto &[first, name] : vectors)
        for (unsigned int d = 0; d < 3; ++d)
          {
            names[first + d] = name;
            kinds[first + d] =
              DataComponentInterpretation::component_is_part_of_vector;
          }

      Particles::DataOut<3> data_out;
      data_out.build_patches(particles, names, kinds);
      DataOutBase::VtkFlags flags;
      flags.time = time;
      data_out.set_flags(flags);
      series.write_step(data_out, step, time, comm);
    }
  } // namespace io
} // namespace softsand
