#ifndef softsand_dem_dem_parameters_h
#define softsand_dem_dem_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <softsand/dem/contact_law.h>
#include <softsand/dem/material.h>
#include <softsand/dem/walls.h>

#include <string>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /**
     * Subsection "dem": material, contact options, walls, time stepping and
     * what a granular scene reports.
     */
    struct DEMParameters
    {
      Material       material;
      WallParameters walls;
      RollingModel   rolling_model = RollingModel::none;

      /// DEM step (s); 0: the automatic fraction of the Rayleigh time.
      double time_step = 0;
      double automatic_rayleigh_fraction = 0.2;
      /// Largest accepted dt / (Rayleigh time of the smallest grain).
      double max_rayleigh_fraction = 0.35;
      /// Adaptive step (time step = 0): largest omega dt and c dt of a grain.
      double stability_number = 0.8;
      Tensor<1, 3> gravity;
      /// Verlet skin as a fraction of the largest grain radius.
      double skin_fraction = 0.25;

      /// Stop once the kinetic energy per grain (J) stays below this value
      /// for 'settled checks' statistics rows (0: never).
      double       settled_kinetic_energy = 0;
      unsigned int settled_checks         = 5;
      unsigned int statistics_interval    = 100;
      unsigned int output_interval        = 0;
      /// Packing fraction probe: box of grain centres (empty: the domain).
      std::vector<double> probe_box;
      /// Write the final pack to this file (grain-file format; empty: no).
      std::string  save_pack;
      /// Write the inserted grains before the first step (empty: no).
      std::string  save_initial_pack;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace dem
} // namespace softsand

#endif
