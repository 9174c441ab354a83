#ifndef softsand_drivers_run_scene_h
#define softsand_drivers_run_scene_h

#include <softsand/core/parameters.h>

#include <map>
#include <string>

namespace softsand
{
  namespace drivers
  {
    /// Runs the one scene of @p parameters in the scene class of its mode
    /// (fluid on fixed grains, coupled, granular); its results.
    template <int dim>
    std::map<std::string, double>
    run_scene(const core::Parameters<dim> &parameters, const MPI_Comm comm);
  } // namespace drivers
} // namespace softsand

#endif
