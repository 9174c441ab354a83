#include <softsand/base/parameter_tools.h>
#include <softsand/dem/material.h>

#include <cmath>
#include <string>

namespace softsand
{
  namespace dem
  {
    double
    Material::rayleigh_time(const double radius) const
    {
      return M_PI * radius * std::sqrt(density / shear_modulus()) /
             (0.1631 * poisson_ratio + 0.8766);
    }


    void
    Material::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("material");
      prm.declare_entry("density", "2500", Patterns::Double(0),
                        "Grain density (kg/m^3).");
      prm.declare_entry("youngs modulus", "5e6", Patterns::Double(0),
                        "Young's modulus Y (Pa); the paper's soft sand uses "
                        "5e6.");
      prm.declare_entry("poisson ratio", "0.15", Patterns::Double(0, 0.5),
                        "Poisson ratio nu in [0, 0.5).");
      prm.declare_entry("restitution", "0.7", Patterns::Double(0, 1),
                        "Normal coefficient of restitution e in (0, 1].");
      prm.declare_entry("friction", "0.7", Patterns::Double(0),
                        "Coulomb friction coefficient mu (grain-grain and "
                        "grain-wall).");
      prm.declare_entry("rolling friction", "0", Patterns::Double(0),
                        "Rolling resistance coefficient mu_r "
                        "(dimensionless); 0 = none.");
      prm.declare_entry("cohesion energy density", "0", Patterns::Double(0),
                        "Simplified-JKR cohesion k (J/m^3): an attractive "
                        "force k A, A the area of the contact circle.");
      prm.declare_entry("wall cohesion energy density", "same as grains",
                        Patterns::Anything(),
                        "Cohesion k (J/m^3) of grain-wall contacts, >= 0, or "
                        "'same as grains' (the entry above). 0 keeps cohesive "
                        "grains from sticking to the walls, so that a "
                        "confined pack carries its pistons' load instead of "
                        "the plates.");
      prm.leave_subsection();
    }


    void
    Material::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("material");
      density                 = prm.get_double("density");
      youngs_modulus          = prm.get_double("youngs modulus");
      poisson_ratio           = prm.get_double("poisson ratio");
      restitution             = prm.get_double("restitution");
      friction                = prm.get_double("friction");
      rolling_friction        = prm.get_double("rolling friction");
      cohesion_energy_density = prm.get_double("cohesion energy density");
      const std::string wall_cohesion_entry =
        prm.get("wall cohesion energy density");
      wall_cohesion_energy_density.reset();
      if (wall_cohesion_entry != "same as grains")
        {
          // The entry's pattern is Anything (it also takes a keyword), so
          // the number is checked here with the pattern of the one above.
          if (!Patterns::Double(0).match(wall_cohesion_entry))
            base::throw_invalid_parameter(
              "dem/material/wall cohesion energy density",
              wall_cohesion_entry,
              "it must be a number >= 0 (J/m^3) or 'same as grains'");
          wall_cohesion_energy_density =
            Utilities::string_to_double(wall_cohesion_entry);
        }
      const auto positive = [&](const std::string &entry, const double v) {
        if (!(v > 0))
          base::throw_invalid_parameter("dem/material/" + entry,
                                        prm.get(entry),
                                        "it must be > 0");
      };
      positive("density", density);
      positive("youngs modulus", youngs_modulus);
      positive("restitution", restitution);
      if (!(poisson_ratio < 0.5))
        base::throw_invalid_parameter("dem/material/poisson ratio",
                                      prm.get("poisson ratio"),
                                      "it must lie in [0, 0.5)");
      prm.leave_subsection();
    }
  } // namespace dem
} // namespace softsand
