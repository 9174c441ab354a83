// Contact laws beyond the normal impact, against closed forms:
//  * simplified-JKR cohesion: two equal grains (R = 0.05 mm, paper's
//    material, k = 1e5, 3e5, 1e6 J/m^3) touching without gravity come to
//    rest where the Hertz force equals k A, A = pi (R delta - delta^2 / 4)
//    the area of the contact circle;
//  * the same for a grain on a wall, A = pi (2 R delta - delta^2), with the
//    wall's own cohesion when it differs from the grains' (1e5 against 1e6),
//    and none when it is 0 (the grain, started overlapping, leaves the wall);
//  * rolling resistance, constant torque model: a grain rolling on the floor
//    under gravity decelerates at 5/7 mu_r g (R* = R for a wall), so it stops
//    after v0^2 / (2 * 5/7 mu_r g);
//  * the elastic-plastic rolling spring reaches the same limiting torque.

#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include "tests.h"

#include <cmath>

using namespace softsand;

namespace
{
  constexpr double R = 5e-5;

  dem::DEMParameters
  material()
  {
    dem::DEMParameters p;
    p.material.density        = 2650;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = 0.5;
    p.material.friction       = 0.7;
    p.time_step = 0.2 * p.material.rayleigh_time(R);
    return p;
  }

  /// Run @p grains for @p steps; return the final grains.
  std::vector<dem::Grain<3>>
  run(const dem::DEMParameters &p, const std::vector<dem::Grain<3>> &grains,
      const unsigned int steps, double *time = nullptr)
  {
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-2e-3, -2e-3, 0), hi(2e-3, 2e-3, 1e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    dem.insert(grains, true);
    dem.initialize();
    for (unsigned int n = 0; n < steps; ++n)
      dem.step();
    if (time)
      *time = dem.time();
    return dem.gather_grains();
  }

  /// Root of f on [a, b] by bisection.
  template <typename F>
  double
  bisect(F f, double a, double b)
  {
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double m = 0.5 * (a + b);
        (f(a) * f(m) <= 0 ? b : a) = m;
      }
    return 0.5 * (a + b);
  }

  /// Closed-form overlap of a grain of radius R resting on a wall with
  /// cohesion @p k and no gravity: Hertz force = k pi (2 R delta - delta^2).
  double
  wall_balance_overlap(const dem::DEMParameters &p, const double k)
  {
    const double y_eff = p.material.effective_youngs_modulus();
    return bisect(
      [&](const double d) {
        return 4. / 3. * y_eff * std::sqrt(R) * std::pow(d, 1.5) -
               k * M_PI * (2 * R * d - d * d);
      },
      1e-3 * R, R);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const double k = 3e5;

  // Cohesive pair; at 1e6 J/m^3 these soft grains balance at 1.9 R*, far
  // beyond Hertz's small overlaps (granular scenes warn there), but the
  // law itself still holds its closed form.
  for (const double pair_k : {1e5, 3e5, 1e6})
    {
      dem::DEMParameters p = material();
      p.material.cohesion_energy_density = pair_k;
      const double y_eff = p.material.effective_youngs_modulus();
      const double r_eff = R / 2;
      const double delta = bisect(
        [&](const double d) {
          return 4. / 3. * y_eff * std::sqrt(r_eff) * std::pow(d, 1.5) -
                 pair_k * M_PI * (R * d - d * d / 4);
        },
        1e-3 * R, R);
      std::vector<dem::Grain<3>> g(2);
      g[0].center = Point<3>(0, 0, 5e-4);
      g[1].center = Point<3>(2 * R - 1e-3 * R, 0, 5e-4);
      g[0].radius = g[1].radius = R;
      const auto out     = run(p, g, 20000);
      const double found = 2 * R - out[0].center.distance(out[1].center);
      deallog << "cohesive pair, k = " << pair_k
              << ": delta / R* = " << std::setprecision(4)
              << found / r_eff << ", closed form " << delta / r_eff
              << ", relative error " << std::setprecision(2)
              << std::abs(found / delta - 1) << std::setprecision(6)
              << ", residual speed below 1e-6 m/s: "
              << (out[0].velocity.norm() < 1e-6 ? "yes" : "no") << std::endl;
    }

  // Cohesive grain on a wall.
  {
    dem::DEMParameters p = material();
    p.material.cohesion_energy_density = k;
    p.walls.list       = "plane 0 0 0 0 0 1 fixed";
    const double delta = wall_balance_overlap(p, k);
    std::vector<dem::Grain<3>> g(1);
    g[0].center = Point<3>(0, 0, R - 1e-3 * R);
    g[0].radius = R;
    const auto out     = run(p, g, 20000);
    const double found = R - out[0].center[2];
    deallog << "cohesive grain on a wall: delta / R = " << std::setprecision(4)
            << found / R << ", closed form " << delta / R
            << ", relative error " << std::setprecision(2)
            << std::abs(found / delta - 1) << std::setprecision(6) << std::endl;
  }

  // A wall cohesion of its own: the balance follows the wall's k, not the
  // grains'; with none, the elastic force pushes the grain off the wall.
  for (const double wall_k : {1e5, 0.})
    {
      dem::DEMParameters p = material();
      p.material.cohesion_energy_density      = 1e6;
      p.material.wall_cohesion_energy_density = wall_k;
      p.walls.list = "plane 0 0 0 0 0 1 fixed";
      std::vector<dem::Grain<3>> g(1);
      // Cohesion pulls a grain touching by 1e-3 R in; without, an overlap of
      // 1e-2 R pushes it off (1,000 steps: it stays inside the box).
      g[0].center = Point<3>(0, 0, R - (wall_k > 0 ? 1e-3 : 1e-2) * R);
      g[0].radius = R;
      const auto out = run(p, g, wall_k > 0 ? 20000 : 1000);
      AssertThrow(out.size() == 1, ExcMessage("the grain left the box"));
      const double found = R - out[0].center[2];
      if (wall_k > 0)
        {
          const double delta = wall_balance_overlap(p, wall_k);
          deallog << "grain on a wall, wall cohesion 1e5, grains 1e6: "
                  << "delta / R = " << std::setprecision(4) << found / R
                  << ", closed form (wall's k) " << delta / R
                  << ", relative error " << std::setprecision(2)
                  << std::abs(found / delta - 1) << std::setprecision(6)
                  << std::endl;
        }
      else
        deallog << "grain on a wall, wall cohesion 0, grains 1e6: left the "
                << "wall: " << (found < 0 ? "yes" : "no")
                << ", speed away (m/s) " << std::setprecision(3)
                << out[0].velocity[2] << std::setprecision(6) << std::endl;
    }

  // Rolling resistance on the floor.
  for (const auto model : {dem::RollingModel::constant_torque,
                           dem::RollingModel::elastic_plastic})
    {
      dem::DEMParameters p = material();
      p.rolling_model             = model;
      p.material.rolling_friction = 0.1;
      p.gravity                   = Tensor<1, 3>({0, 0, -9.81});
      p.walls.list                = "plane 0 0 0 0 0 1 fixed";
      // Start resting on the floor at its static overlap, rolling at v0.
      const double mass  = 2650 * 4. / 3. * M_PI * R * R * R;
      const double y_eff = p.material.effective_youngs_modulus();
      const double rest  = std::pow(mass * 9.81 / (4. / 3. * y_eff * std::sqrt(R)),
                                   2. / 3.);
      const double v0 = 2e-3;
      std::vector<dem::Grain<3>> g(1);
      g[0].center   = Point<3>(-1.5e-3, 0, R - rest);
      g[0].radius   = R;
      g[0].velocity = Tensor<1, 3>({v0, 0, 0});
      g[0].angular_velocity = Tensor<1, 3>({0, v0 / (R - 0.5 * rest), 0});
      const double decel     = 5. / 7. * 0.1 * 9.81;
      const double stop_time = v0 / decel;
      const unsigned int steps =
        static_cast<unsigned int>(0.5 * stop_time / p.time_step);
      double     t;
      const auto out = run(p, g, steps, &t);
      const double expected = v0 - decel * t;
      deallog << (model == dem::RollingModel::constant_torque ?
                    "rolling, constant torque: " :
                    "rolling, elastic-plastic: ")
              << "speed at half the stopping time / (v0 - 5/7 mu_r g t) = "
              << std::setprecision(3) << out[0].velocity[0] / expected
              << std::setprecision(6) << std::endl;
    }
}
