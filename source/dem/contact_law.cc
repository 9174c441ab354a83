#include <softsand/dem/contact_law.h>

#include <algorithm>
#include <cmath>

namespace softsand
{
  namespace dem
  {
    double
    hertz_restitution(const double beta)
    {
      // RK4 on x'' = -x^{3/2} - c x^{1/4} x', x(0) = 0, x'(0) = 1, until the
      // grains separate (x back to 0); the contact lasts about 3.2 time
      // units, so 2e4 steps resolve e to far better than 1e-6.
      const double c   = std::sqrt(5.) * std::abs(beta);
      const auto   acc = [c](const double x, const double v) {
        const double xp = std::max(x, 0.);
        return -xp * std::sqrt(xp) - c * std::sqrt(std::sqrt(xp)) * v;
      };
      const double h = 2e-4;
      double       x = 0, v = 1;
      for (unsigned int step = 0; step < 1000000; ++step)
        {
          const double k1x = v, k1v = acc(x, v);
          const double k2x = v + 0.5 * h * k1v,
                       k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
          const double k3x = v + 0.5 * h * k2v,
                       k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
          const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
          const double x_new = x + h / 6. * (k1x + 2 * k2x + 2 * k3x + k4x);
          const double v_new = v + h / 6. * (k1v + 2 * k2v + 2 * k3v + k4v);
          if (step > 0 && x_new <= 0)
            {
              // Velocity at the crossing, interpolated linearly in x.
              const double s = x / (x - x_new);
              return -(v + s * (v_new - v));
            }
          x = x_new;
          v = v_new;
        }
      return 0; // never separates: fully damped
    }


    double
    damping_factor(const double e)
    {
      if (e >= 1)
        return 0;
      const double log_e = std::log(e);
      return log_e / std::sqrt(log_e * log_e + M_PI * M_PI);
    }


    ContactLaw::ContactLaw(const Material &material, const RollingModel rolling)
      : y_eff(material.effective_youngs_modulus())
      , g_eff(material.effective_shear_modulus())
      , damping_beta(damping_factor(material.restitution))
      , mu(material.friction)
      , mu_rolling(material.rolling_friction)
      , cohesion(material.cohesion_energy_density)
      , rolling_model(rolling)
    {
      const double c = -2. * std::sqrt(5. / 6.) * damping_beta;
      damping_n      = c * std::sqrt(2. * y_eff);
      damping_t      = c * std::sqrt(8. * g_eff);
    }
  } // namespace dem
} // namespace softsand
