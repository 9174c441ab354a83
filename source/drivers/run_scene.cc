#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/coupled_scene.h>
#include <softsand/drivers/fluid_scene.h>
#include <softsand/drivers/granular_scene.h>
#include <softsand/drivers/run_scene.h>

namespace softsand
{
  namespace drivers
  {
    template <int dim>
    std::map<std::string, double>
    run_scene(const core::Parameters<dim> &parameters, const MPI_Comm comm)
    {
      using Mode      = core::SimulationControl::Mode;
      const Mode mode = parameters.simulation_control.mode;
      if (mode == Mode::granular || mode == Mode::coupled)
        {
          // The DEM is 3D.
          if constexpr (dim == 3)
            {
              if (mode == Mode::granular)
                {
                  GranularScene scene(parameters, comm);
                  scene.run();
                  return scene.results();
                }
              CoupledScene scene(parameters, comm);
              scene.run();
              return scene.results();
            }
          else
            base::throw_invalid_parameter(
              "simulation control/mode",
              mode == Mode::granular ? "granular" : "coupled",
              mode == Mode::granular ?
                "granular scenes are 3D (set dimension = 3)" :
                "coupled (CFD-DEM) scenes are 3D (set dimension = 3): the "
                "DEM is 3D");
        }
      FluidScene<dim> scene(parameters, comm);
      scene.run();
      return scene.results();
    }

    template std::map<std::string, double>
    run_scene(const core::Parameters<2> &, const MPI_Comm);
    template std::map<std::string, double>
    run_scene(const core::Parameters<3> &, const MPI_Comm);
  } // namespace drivers
} // namespace softsand
