#include <softsand/base/parameter_tools.h>
#include <softsand/dem/material.h>

#include <cmath>

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
