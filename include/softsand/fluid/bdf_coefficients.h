#ifndef softsand_fluid_bdf_coefficients_h
#define softsand_fluid_bdf_coefficients_h

#include <deal.II/base/exceptions.h>

namespace softsand
{
  namespace fluid
  {
    /**
     * Backward differences on steps of changing length: with
     * omega = dt_n / dt_(n-1) (this step over the last),
     *
     *   du/dt ~ (a0 u^(n+1) + a1 u^n + a2 u^(n-1)) / dt_n,
     *   u^(n+1) ~ e1 u^n + e2 u^(n-1)   (the advecting velocity),
     *
     * exact for linear u (BDF1: a0 = 1, a1 = -1, e1 = 1). BDF2 has
     * a0 = (1 + 2 omega) / (1 + omega), a1 = -(1 + omega),
     * a2 = omega^2 / (1 + omega); equal steps give 3/2, -2, 1/2. It is
     * zero-stable for omega < 1 + sqrt(2), so a doubled step keeps second
     * order and a mass term 5/3 rho / dt instead of restarting with BDF1's
     * rho / dt, where convection weighs 1.5x more.
     */
    struct BDFCoefficients
    {
      double a0 = 1, a1 = -1, a2 = 0;
      double e1 = 1, e2 = 0;
    };

    /// The largest step ratio omega that keeps BDF2 (zero stability).
    constexpr double max_bdf2_step_ratio = 2.4;

    inline BDFCoefficients
    bdf_coefficients(const unsigned int order, const double omega)
    {
      Assert(order == 1 || order == 2, dealii::ExcIndexRange(order, 1, 3));
      Assert(omega > 0, dealii::ExcMessage("step ratio must be positive"));
      BDFCoefficients c;
      if (order == 2)
        {
          c.a0 = (1. + 2. * omega) / (1. + omega);
          c.a1 = -(1. + omega);
          c.a2 = omega * omega / (1. + omega);
          c.e1 = 1. + omega;
          c.e2 = -omega;
        }
      return c;
    }
  } // namespace fluid
} // namespace softsand

#endif
