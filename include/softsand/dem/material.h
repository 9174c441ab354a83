#ifndef softsand_dem_material_h
#define softsand_dem_material_h

#include <deal.II/base/parameter_handler.h>

#include <optional>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /**
     * Mechanical properties of the grains (one material per scene; walls
     * share them, except perhaps the cohesion, and are rigid and infinitely
     * massive).
     */
    struct Material
    {
      double density          = 2500;  ///< kg/m^3
      double youngs_modulus   = 5e6;   ///< Y (Pa)
      double poisson_ratio    = 0.15;  ///< nu
      double restitution      = 0.7;   ///< normal coefficient e in (0, 1]
      double friction         = 0.7;   ///< Coulomb coefficient mu
      double rolling_friction = 0;     ///< mu_r (dimensionless)
      /// Simplified-JKR cohesion energy density k (J/m^3): F = k A.
      double cohesion_energy_density = 0;
      /// The same for grain-wall contacts; unset: the grains' value. Cohesive
      /// grains stuck to the plates of a Hele-Shaw cell let the plates carry
      /// the pistons' load instead of the pack.
      std::optional<double> wall_cohesion_energy_density;

      /// The cohesion energy density of a grain-wall contact (J/m^3).
      double
      wall_cohesion() const
      {
        return wall_cohesion_energy_density.value_or(cohesion_energy_density);
      }

      /// This material with the grain-wall cohesion as its cohesion: what
      /// the contact law of grain-wall contacts uses.
      Material
      wall_material() const
      {
        Material m                = *this;
        m.cohesion_energy_density = wall_cohesion();
        return m;
      }

      /// Shear modulus G = Y / (2 (1 + nu)).
      double
      shear_modulus() const
      {
        return youngs_modulus / (2. * (1. + poisson_ratio));
      }

      /// Effective modulus Y* of a grain-grain contact (equal materials).
      double
      effective_youngs_modulus() const
      {
        return youngs_modulus /
               (2. * (1. - poisson_ratio * poisson_ratio));
      }

      /// Effective shear modulus G* of a grain-grain contact.
      double
      effective_shear_modulus() const
      {
        return youngs_modulus /
               (4. * (2. - poisson_ratio) * (1. + poisson_ratio));
      }

      /// Rayleigh time pi R sqrt(rho / G) / (0.1631 nu + 0.8766) of a grain
      /// of radius @p radius: the shear-wave transit time that bounds the
      /// stable DEM step.
      double
      rayleigh_time(const double radius) const;

      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the current subsection; names "dem/material/..." in errors.
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace dem
} // namespace softsand

#endif
