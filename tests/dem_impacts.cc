// Binary impacts with the paper's material (Y = 5e6 Pa, nu = 0.15,
// mu = 0.7, 0.1 mm grains, 2500 kg/m^3) at 0.1 m/s and dt = 20% of the
// Rayleigh time: Hertz contact time and maximum overlap for e = 1, the
// rebound restitution for e = 0.2 ... 1 (sphere-wall and sphere-sphere),
// and an oblique impact against the gross-sliding solution. Restitution is
// measured for 8 positions of the contact onset within a time step (the
// initial gap varied by fractions of v dt): the worst error over them is
// what a pack of grains sees.

#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include "tests.h"

#include <cmath>

using namespace softsand;

namespace
{
  constexpr double radius = 5e-5, speed = 0.1;

  struct Impact
  {
    double contact_time = 0, max_overlap = 0, restitution = 0;
    double tangential_velocity = 0, spin = 0, normal_in = 0, tangential_in = 0;
  };

  dem::DEMParameters
  material(const double e, const double rayleigh_fraction = 0.2)
  {
    dem::DEMParameters p;
    p.material.density        = 2500;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = e;
    p.material.friction       = 0.7;
    p.time_step = rayleigh_fraction * p.material.rayleigh_time(radius);
    return p;
  }

  /// One impact: on the wall z = 0 (pair = false) or of a grain moving
  /// along -x onto a grain at rest (pair = true); @p tangential is the
  /// speed along x of a wall impact. The initial gap is 0.05 R plus
  /// @p onset_phase times the distance v dt of one step.
  Impact
  run(const dem::DEMParameters &p,
      const bool                pair,
      const double              tangential,
      const double              onset_phase = 0)
  {
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-1e-3, -1e-3, -1e-3), hi(1e-3, 1e-3, 1e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::DEMParameters parameters = p;
    if (!pair)
      parameters.walls.list = "plane 0 0 0 0 0 1 fixed";
    dem::GranularDynamics dem(tria, parameters,
                              BoundingBox<3>(std::make_pair(lo, hi)));
    std::vector<dem::Grain<3>> grains(pair ? 2 : 1);
    const double gap = 0.05 * radius + onset_phase * speed * p.time_step;
    if (pair)
      {
        grains[0].center   = Point<3>(2 * radius + gap, 0, 0);
        grains[0].velocity = Tensor<1, 3>({-speed, 0, 0});
        grains[1].center   = Point<3>(0, 0, 0);
      }
    else
      {
        grains[0].center   = Point<3>(0, 0, radius + gap);
        grains[0].velocity = Tensor<1, 3>({tangential, 0, -speed});
      }
    for (auto &g : grains)
      g.radius = radius;
    dem.insert(grains, true);
    dem.initialize();

    const auto overlap = [&](const std::vector<dem::Grain<3>> &g) {
      return pair ? 2 * radius - g[0].center.distance(g[1].center) :
                    radius - g[0].center[2];
    };
    Impact result;
    std::vector<double> history(1, overlap(dem.gather_grains()));
    double t_start = -1, t_end = -1;
    for (unsigned int n = 0; n < 100000 && t_end < 0; ++n)
      {
        const double before = history.back();
        dem.step();
        const double now = overlap(dem.gather_grains());
        history.push_back(now);
        const double t = dem.time();
        if (t_start < 0 && now > 0)
          t_start = t - dem.time_step() * now / (now - before);
        else if (t_start >= 0 && now <= 0)
          t_end = t - dem.time_step() * now / (now - before);
      }
    result.contact_time = t_end - t_start;
    // Maximum overlap: vertex of the parabola through the top three samples.
    const auto top = std::max_element(history.begin(), history.end());
    const double a = *(top - 1), b = *top, c = *(top + 1);
    result.max_overlap = b + (a - c) * (a - c) / (8 * (2 * b - a - c));

    const auto g = dem.gather_grains();
    if (pair)
      result.restitution = (g[0].velocity[0] - g[1].velocity[0]) / speed;
    else
      {
        result.restitution         = g[0].velocity[2] / speed;
        result.tangential_velocity = g[0].velocity[0];
        result.spin                = g[0].angular_velocity[1];
      }
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const double mass = 2500 * 4. / 3. * M_PI * std::pow(radius, 3);
  // Hertz: delta_max = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5) and
  // t_c = 2 I delta_max / v, I = int_0^1 (1 - x^(5/2))^(-1/2) dx
  //     = (2/5) Gamma(2/5) Gamma(1/2) / Gamma(9/10).
  const double integral =
    0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  const dem::DEMParameters elastic = material(1.0);
  const double y_eff = elastic.material.effective_youngs_modulus();

  deallog << "dt / Rayleigh time = "
          << elastic.time_step / elastic.material.rayleigh_time(radius)
          << std::endl;
  for (const bool pair : {false, true})
    {
      const double r_eff = pair ? radius / 2 : radius;
      const double m_eff = pair ? mass / 2 : mass;
      const double delta_max = std::pow(
        15 * m_eff * speed * speed / (16 * y_eff * std::sqrt(r_eff)), 0.4);
      const double t_c = 2 * integral * delta_max / speed;
      const Impact r = run(elastic, pair, 0);
      const double e_tc = r.contact_time / t_c - 1;
      const double e_dm = r.max_overlap / delta_max - 1;
      deallog << (pair ? "sphere-sphere" : "sphere-wall  ")
              << " e=1: contact time / Hertz - 1 = " << std::setprecision(4)
              << e_tc << ", max overlap / Hertz - 1 = " << e_dm
              << std::setprecision(6) << "  within 0.5%: "
              << (std::abs(e_tc) < 5e-3 && std::abs(e_dm) < 5e-3 ? "yes" : "NO")
              << std::endl;
    }

  // The beta(e) of LIGGGHTS hertz against the continuous Hertz contact.
  for (const double e : {0.7, 0.5, 0.2})
    deallog << "e=" << std::setprecision(2) << e << ": beta "
            << std::setprecision(5) << dem::damping_factor(e)
            << ", rebound of the Hertz ODE "
            << dem::hertz_restitution(dem::damping_factor(e))
            << std::setprecision(6) << std::endl;
  const unsigned int n_phases = 8;
  for (const double fraction : {0.2, 0.1})
    for (const bool pair : {false, true})
      for (const double e : {1.0, 0.7, 0.5, 0.2, 0.1})
        {
          if (fraction < 0.2 && e > 0.2)
            continue;
          // Error at onset phase 0, and the extremes over all phases.
          double first = 0, lowest = 1, highest = -1;
          for (unsigned int k = 0; k < n_phases; ++k)
            {
              const Impact r =
                run(material(e, fraction), pair, 0, double(k) / n_phases);
              const double err = r.restitution / e - 1;
              if (k == 0)
                first = err;
              lowest  = std::min(lowest, err);
              highest = std::max(highest, err);
            }
          const double worst = std::max(-lowest, highest);
          deallog << "dt=" << std::setprecision(1) << fraction << " T_R"
                  << (pair ? " sphere-sphere" : " sphere-wall  ")
                  << " e_in=" << std::setprecision(2) << e
                  << " rel.error=" << std::setprecision(3) << first
                  << ", over " << n_phases << " onset phases ["
                  << lowest << ", " << highest << "]" << std::setprecision(6)
                  << "  within 1%: " << (worst < 0.01 ? "yes" : "NO")
                  << std::endl;
        }

  // Oblique impact at 78.7 degrees from the normal: v_t / v_n = 5 exceeds
  // 7/2 mu (1 + e) = 4.17, so the grain slides through the whole contact.
  {
    const dem::DEMParameters p = material(0.7);
    const double vt = 5 * speed;
    const Impact r = run(p, false, vt);
    const double mu = 0.7, e = r.restitution;
    const double vt_ref = vt - mu * (1 + e) * speed;
    const double w_ref  = 5 * mu * (1 + e) * speed / (2 * radius);
    deallog << "oblique: e_out=" << std::setprecision(4) << e
            << " v_t'/gross sliding - 1 = " << std::setprecision(3)
            << r.tangential_velocity / vt_ref - 1
            << ", w'/gross sliding - 1 = " << r.spin / w_ref - 1
            << std::setprecision(6) << std::endl;
  }
}
