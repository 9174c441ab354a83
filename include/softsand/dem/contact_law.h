#ifndef softsand_dem_contact_law_h
#define softsand_dem_contact_law_h

#include <deal.II/base/tensor.h>

#include <softsand/dem/material.h>

#include <cmath>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /// What a contact remembers between steps: the tangential spring
    /// displacement, the elastic rolling torque, and for the normal damping
    /// its potential Gamma(delta) = int_0^delta gamma_n(s) ds (N s) and the
    /// normal damping force (N, along n) of the last evaluation.
    struct ContactHistory
    {
      Tensor<1, 3> shear;
      Tensor<1, 3> rolling_torque;
      double       damping_potential = 0;
      double       damping_force     = 0;

      /// Forget the contact. Most neighbour pairs are apart and already
      /// clear: they are only read, not written (a whole-struct assignment
      /// through a temporary was 17 % of the force loop of a pour).
      void
      clear()
      {
        if (damping_potential != 0 || damping_force != 0 ||
            shear.norm_square() != 0 || rolling_torque.norm_square() != 0)
          {
            shear             = Tensor<1, 3>();
            rolling_torque    = Tensor<1, 3>();
            damping_potential = 0;
            damping_force     = 0;
          }
      }
    };

    /// Rolling resistance: none, constant directional torque (CDT), or the
    /// elastic-plastic spring (EPSD, without dashpot as LIGGGHTS' epsd2).
    enum class RollingModel
    {
      none,
      constant_torque,
      elastic_plastic
    };

    /// The damping factor beta = ln e / sqrt(ln^2 e + pi^2) (<= 0) of
    /// restitution @p e. With the damping 2 sqrt(5/6) beta sqrt(S_n m*) of a
    /// Hertz spring this relation is exact: hertz_restitution(beta) = e
    /// (checked by the test dem_impacts).
    double
    damping_factor(const double e);

    /// Restitution of the dimensionless Hertz contact
    /// x'' + sqrt(5) |beta| x^(1/4) x' + x^(3/2) = 0 (what the contact law
    /// below gives in the limit of small steps).
    double
    hertz_restitution(const double beta);

    /**
     * The contact law of LIGGGHTS `hertz` + `tangential history` +
     * `cohesion sjkr` + rolling resistance, for a grain i touching a grain
     * or a wall j:
     *   k_n = 4/3 Y* sqrt(R* delta), k_t = 8 G* sqrt(R* delta),
     *   gamma_{n,t} = -2 sqrt(5/6) beta sqrt(S_{n,t} m*), S_n = 2 Y*
     *   sqrt(R* delta), S_t = k_t,
     *   F_n = (k_n delta - gamma_n v_n) n - k A n,
     *   F_t = -k_t xi - gamma_t v_t, |F_t| <= mu |k_n delta - gamma_n v_n|.
     *
     * The normal damping force is an exact time derivative:
     * -gamma_n(delta) v_n = d/dt Gamma(delta), Gamma(delta) = int_0^delta
     * gamma_n = 4/5 gamma_n(delta) delta. Its impulse over a step is
     * therefore Gamma(delta_new) - Gamma(delta_old) along n, whatever the
     * velocity in between; evaluate() returns what the end-of-step kick
     * must add so that the step's normal damping impulse is exactly that
     * (see GranularDynamics::step()).
     *
     * Header-only: this is the innermost loop of the DEM.
     */
    class ContactLaw
    {
    public:
      ContactLaw() = default;
      ContactLaw(const Material &material, const RollingModel rolling);

      /**
       * Force on i and torques on i and j of one contact.
       * @p n unit normal from j to i, @p delta overlap (> 0),
       * @p lever_i / @p lever_j distances from the centres to the contact
       * point (lever_j = 0 for a wall), @p r_eff, @p m_eff effective radius
       * and mass, @p v_rel velocity of i relative to j at the contact point,
       * @p v_slide the same over the step (from the velocities of the
       * drift, t + dt/2: dt v_slide is how far the contact point slid, which
       * loads the tangential spring; the end-of-step @p v_rel there put the
       * spring half a step ahead, an extra dashpot k_t dt / 2 that gave 16-19 %
       * too much spin in oblique impacts at 0.2 T_R),
       * @p w_rel angular velocity of i minus that of j, @p area the area of
       * the contact circle (for cohesion).
       *
       * @p damping_impulse (N s, along n on i): to add in the end-of-step
       * kick, instead of dt/2 times the normal damping force in @p force_i,
       * so that the normal damping impulse of the step is
       * Gamma(delta) - Gamma(delta_old) (delta_old from the history, or
       * estimated as delta + dt v_n when the contact is new).
       */
      DEAL_II_ALWAYS_INLINE inline void
      evaluate(const Tensor<1, 3> &n,
               const double        delta,
               const double        lever_i,
               const double        lever_j,
               const double        r_eff,
               const double        m_eff,
               const Tensor<1, 3> &v_rel,
               const Tensor<1, 3> &v_slide,
               const Tensor<1, 3> &w_rel,
               const double        area,
               const double        dt,
               ContactHistory     &history,
               Tensor<1, 3>       &force_i,
               Tensor<1, 3>       &torque_i,
               Tensor<1, 3>       &torque_j,
               double             &stiffness,
               double             &damping,
               double             &damping_impulse) const;

      /// The end-of-step impulse (N s, along n on i) of a contact that
      /// opened during the step: its damping potential goes back to zero.
      double
      separation_impulse(const ContactHistory &history, const double dt) const
      {
        return -(history.damping_potential + 0.5 * dt * history.damping_force);
      }

      /// Elastic normal force 4/3 Y* sqrt(R*) delta^(3/2) (for statistics).
      double
      elastic_normal_force(const double r_eff, const double delta) const
      {
        return 4. / 3. * y_eff * std::sqrt(r_eff * delta) * delta;
      }

      double
      beta() const
      {
        return damping_beta;
      }

    private:
      double       y_eff = 0, g_eff = 0, damping_beta = 0;
      /// -2 sqrt(5/6) beta sqrt(2 Y*) and -2 sqrt(5/6) beta sqrt(8 G*).
      double       damping_n = 0, damping_t = 0;
      double       mu = 0, mu_rolling = 0, cohesion = 0;
      RollingModel rolling_model = RollingModel::none;
    };


    DEAL_II_ALWAYS_INLINE inline void
    ContactLaw::evaluate(const Tensor<1, 3> &n,
                         const double        delta,
                         const double        lever_i,
                         const double        lever_j,
                         const double        r_eff,
                         const double        m_eff,
                         const Tensor<1, 3> &v_rel,
                         const Tensor<1, 3> &v_slide,
                         const Tensor<1, 3> &w_rel,
                         const double        area,
                         const double        dt,
                         ContactHistory     &history,
                         Tensor<1, 3>       &force_i,
                         Tensor<1, 3>       &torque_i,
                         Tensor<1, 3>       &torque_j,
                         double             &stiffness,
                         double             &damping,
                         double             &damping_impulse) const
    {
      // gamma_{n,t} = -2 sqrt(5/6) beta sqrt(S_{n,t} m*) with S_n = 2 Y* root,
      // S_t = 8 G* root: one square root serves both.
      const double root    = std::sqrt(r_eff * delta);
      const double kn      = 4. / 3. * y_eff * root;
      const double kt      = 8. * g_eff * root;
      const double sqrt_rm = std::sqrt(root * m_eff);
      const double gamma_n = damping_n * sqrt_rm;
      const double gamma_t = damping_t * sqrt_rm;
      // What this contact adds to a grain's stiffness and damping; the
      // tangential terms act on 2/7 of the mass (rolling couples rotation).
      stiffness = kn + 3.5 * kt;
      damping   = gamma_n + 3.5 * gamma_t;

      const double       vn   = v_rel * n;
      const Tensor<1, 3> vt   = v_rel - vn * n;
      const double       fd   = -gamma_n * vn;
      const double       fn   = kn * delta + fd;
      const double       fcoh = cohesion * area;

      // Normal damping impulse of the step, Gamma(delta) - Gamma(delta_old),
      // minus the dt/2 fd_old of the first half kick and the dt/2 fd that
      // the final kick applies through force_i. Velocity Verlet with the
      // force gamma_n(delta) v_n alone puts this impulse wrong in the step
      // where the contact opens (gamma_n grows as delta^(1/4) from zero): the
      // restitution at e = 0.2 and dt = 0.2 T_R then depends on where in
      // the step the contact starts, from -5% to +1.5%.
      damping_impulse = 0;
      if (damping_n != 0)
        {
          const double potential     = 0.8 * gamma_n * delta;
          double       old_potential = history.damping_potential;
          if (!(old_potential > 0))
            {
              // New contact (or a history lost in migration): the overlap
              // one step back from the current normal velocity.
              const double delta_old = delta + dt * vn;
              old_potential =
                delta_old > 0 ?
                  0.8 * damping_n *
                    std::sqrt(std::sqrt(r_eff * delta_old) * m_eff) *
                    delta_old :
                  0.;
            }
          damping_impulse = potential - old_potential -
                            0.5 * dt * (history.damping_force + fd);
          history.damping_potential = potential;
          history.damping_force     = fd;
        }

      // Tangential spring: rotate into the current tangent plane keeping its
      // length, then stretch by the tangential slide of this step.
      Tensor<1, 3> &xi         = history.shear;
      const double  xi_normal  = xi * n;
      if (xi_normal != 0)
        {
          const double len2 = xi.norm_square();
          xi -= xi_normal * n;
          const double len2_new = xi.norm_square();
          if (len2_new > 0)
            xi *= std::sqrt(len2 / len2_new);
        }
      xi += dt * (v_slide - (v_slide * n) * n);
      Tensor<1, 3> ft       = -kt * xi - gamma_t * vt;
      const double ft_len2  = ft.norm_square();
      const double ft_max   = mu * std::abs(fn);
      if (ft_len2 > ft_max * ft_max)
        {
          // Gross sliding: cap at the Coulomb limit and set the spring to
          // what that force needs, so that sticking resumes smoothly.
          ft *= ft_max / std::sqrt(ft_len2);
          xi = -(ft + gamma_t * vt) / kt;
        }

      force_i = (fn - fcoh) * n + ft;
      // Torques of the tangential force about each centre: the contact
      // point is at -lever_i n from i and +lever_j n from j.
      const Tensor<1, 3> n_cross_ft = cross_product_3d(n, ft);
      torque_i = -lever_i * n_cross_ft;
      torque_j = -lever_j * n_cross_ft;

      if (rolling_model != RollingModel::none && mu_rolling > 0)
        {
          const Tensor<1, 3> w_roll  = w_rel - (w_rel * n) * n;
          const double       limit   = mu_rolling * r_eff * std::abs(fn);
          Tensor<1, 3>       m_roll;
          if (rolling_model == RollingModel::constant_torque)
            {
              const double w_len = w_roll.norm();
              if (w_len > 1e-14)
                m_roll = -(limit / w_len) * w_roll;
            }
          else
            {
              Tensor<1, 3> &m       = history.rolling_torque;
              const double  m_len   = m.norm();
              m -= (m * n) * n;
              const double m_len_new = m.norm();
              if (m_len_new > 0)
                m *= m_len / m_len_new;
              const double kr =
                2.25 * kn * mu_rolling * mu_rolling * r_eff * r_eff;
              m -= kr * dt * w_roll;
              const double len = m.norm();
              if (len > limit)
                m *= limit / len;
              m_roll = m;
            }
          torque_i += m_roll;
          torque_j -= m_roll;
        }
    }
  } // namespace dem
} // namespace softsand

#endif
