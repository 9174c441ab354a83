#ifndef softsand_dem_grain_parameters_h
#define softsand_dem_grain_parameters_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>

#include <softsand/dem/grain.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace dem
  {
    /**
     * Where the grains of a scene come from: an explicit list, a pack file
     * (x y [z] radius [velocities]), a lattice (simple cubic, BCC) or a
     * random non-overlapping pack at a target solid fraction.
     */
    template <int dim>
    struct GrainParameters
    {
      enum class Source
      {
        none,
        list,
        file,
        simple_cubic,
        bcc,
        random
      };
      Source      source = Source::none;
      std::string list;
      std::string file;
      /// Start the grains of a file at rest instead of its velocities.
      bool zero_file_velocities = false;
      double      diameter        = 1e-4;
      double      lattice_spacing = 2e-4;
      bool        region_is_domain = true;
      Point<dim>  region_lower, region_upper;
      double      solid_fraction = 0.3;
      /// Random pack: number of grains (0: by solid fraction).
      unsigned int count = 0;
      /// Largest overlap / R* accepted in a file or list, and of a grain
      /// with a wall at the start (R* = R).
      double       max_overlap_ratio = 0.3;
      std::vector<double> discrete_diameters, discrete_fractions;
      unsigned int seed          = 1;
      std::string  size_distribution = "constant";
      double       min_diameter = 0, max_diameter = 0, mean_diameter = 0,
             diameter_sd = 0;
      Tensor<1, dim> velocity;
      Tensor<1, 3>   angular_velocity;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace dem
} // namespace softsand

#endif
