// Cylinder walls (grains inside), with the axis along (1, 1, 0)/sqrt(2) so
// that the projection onto the axis is exercised.
//
// 1. A frictionless elastic grain (e = 1, mu = 0, R = 0.05 mm, the paper's
//    Y and nu) crosses a cylinder of radius 1 mm obliquely (60 degrees from
//    the radial direction, with an axial component) and bounces off it.
//    At every step of the contact the force on the wall must point from the
//    axis through the grain centre and have the Hertz magnitude
//    4/3 Y* sqrt(R) delta^(3/2) of the exact overlap
//    delta = R - (R_c - rho), rho the centre's distance from the axis.
//    The force is central about the axis and normal to it, so the axial
//    velocity and the angular momentum about the axis are conserved, and
//    with e = 1 the speed comes back.
// 2. A grain (R = 0.5 mm, mu = 0.7, e = 0.7) rolls at the bottom of a
//    horizontal cylinder of radius 5 mm under gravity, released 0.1 rad
//    from the bottom: a rolling pendulum of period
//    T = 2 pi sqrt(7 (R_c - R) / (5 g)) (1 + theta_0^2 / 16), 15% longer
//    than that of a sliding grain; rolling without slip, |w| R = |v|.

#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include "tests.h"

#include <cmath>

using namespace softsand;

namespace
{
  const Tensor<1, 3> axis({1 / std::sqrt(2.), 1 / std::sqrt(2.), 0});
  // Two unit vectors normal to the axis: vertical and horizontal.
  const Tensor<1, 3> e_up({0, 0, 1});
  const Tensor<1, 3> e_side({-1 / std::sqrt(2.), 1 / std::sqrt(2.), 0});

  dem::DEMParameters
  parameters(const double radius,
             const double cylinder_radius,
             const double e,
             const double mu)
  {
    dem::DEMParameters p;
    p.material.density        = 2500;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = e;
    p.material.friction       = mu;
    p.time_step               = 0.2 * p.material.rayleigh_time(radius);
    std::ostringstream wall;
    wall << "cylinder 0 0 0 " << axis[0] << ' ' << axis[1] << ' ' << axis[2]
         << ' ' << cylinder_radius;
    p.walls.list = wall.str();
    return p;
  }

  /// Centre's offset from the axis.
  Tensor<1, 3>
  radial(const Point<3> &x)
  {
    Tensor<1, 3> d = x;
    return d - (d * axis) * axis;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // 1. Frictionless elastic bounce.
  {
    const double                            r = 5e-5, r_c = 1e-3, speed = 0.1;
    const dem::DEMParameters                p = parameters(r, r_c, 1.0, 0.0);
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-1.1e-3, -1.1e-3, -1.1e-3), hi(1.1e-3, 1.1e-3, 1.1e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    std::vector<dem::Grain<3>> grains(1);
    grains[0].radius   = r;
    grains[0].center   = Point<3>(3e-4 * e_up + 1e-4 * axis);
    const double angle = M_PI / 3;
    grains[0].velocity =
      speed * (std::cos(angle) * e_up + std::sin(angle) * e_side) +
      0.3 * speed * axis;
    dem.insert(grains, true);
    dem.initialize();

    const auto angular_momentum = [](const dem::Grain<3> &g) {
      return cross_product_3d(radial(g.center), g.velocity) * axis;
    };
    const double y_eff       = p.material.effective_youngs_modulus();
    const double l_0         = angular_momentum(grains[0]);
    const double axial_0     = grains[0].velocity * axis;
    double       worst_angle = 0, worst_force = 0, max_overlap = 0;
    unsigned int contact_steps = 0, steps_after = 0;
    while (steps_after < 100 && dem.step_number() < 100000)
      {
        dem.step();
        const dem::Grain<3> g     = dem.gather_grains()[0];
        const Tensor<1, 3>  rho   = radial(g.center);
        const double        delta = r - (r_c - rho.norm());
        const Tensor<1, 3> &force = dem.get_walls()[0].force;
        if (delta > 0)
          {
            ++contact_steps;
            max_overlap        = std::max(max_overlap, delta);
            const double hertz = 4. / 3. * y_eff * std::sqrt(r * delta) * delta;
            worst_force =
              std::max(worst_force, std::abs(force.norm() / hertz - 1));
            const Tensor<1, 3> off = force / force.norm() - rho / rho.norm();
            worst_angle            = std::max(worst_angle, off.norm());
          }
        else if (contact_steps > 0)
          ++steps_after;
      }
    const dem::Grain<3> g = dem.gather_grains()[0];
    deallog << "bounce: contact steps > 10: "
            << (contact_steps > 10 ? "yes" : "NO") << ", max overlap / R "
            << std::setprecision(3) << max_overlap / r << std::setprecision(6)
            << std::endl;
    deallog << "bounce: force direction off the radial by < 1e-12: "
            << (worst_angle < 1e-12 ? "yes" : "NO")
            << ", Hertz force of the exact overlap within 1e-9: "
            << (worst_force < 1e-9 ? "yes" : "NO") << std::endl;
    deallog << "bounce: axial velocity kept within 1e-12: "
            << (std::abs(g.velocity * axis / axial_0 - 1) < 1e-12 ? "yes" :
                                                                    "NO")
            << ", angular momentum about the axis within 1e-9: "
            << (std::abs(angular_momentum(g) / l_0 - 1) < 1e-9 ? "yes" : "NO")
            << ", speed within 1e-3: "
            << (std::abs(g.velocity.norm() / grains[0].velocity.norm() - 1) <
                    1e-3 ?
                  "yes" :
                  "NO")
            << ", radial velocity reversed: "
            << (g.velocity * radial(g.center) < 0 ? "yes" : "NO") << std::endl;
  }

  // 2. Rolling pendulum.
  {
    const double       r = 5e-4, r_c = 5e-3, g = 9.81, theta_0 = 0.1;
    dem::DEMParameters p = parameters(r, r_c, 0.7, 0.7);
    p.gravity            = -g * e_up;
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-5.5e-3, -5.5e-3, -5.5e-3), hi(5.5e-3, 5.5e-3, 5.5e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    std::vector<dem::Grain<3>> grains(1);
    grains[0].radius = r;
    grains[0].center = Point<3>(
      (r_c - r) * (std::sin(theta_0) * e_side - std::cos(theta_0) * e_up));
    dem.insert(grains, true);
    dem.initialize();

    const auto theta = [](const Point<3> &x) {
      return std::atan2(Tensor<1, 3>(x) * e_side, -(Tensor<1, 3>(x) * e_up));
    };
    const double period = 2 * M_PI * std::sqrt(7 * (r_c - r) / (5 * g)) *
                          (1 + theta_0 * theta_0 / 16);
    std::vector<double> crossings;
    double              worst_slip = 0;
    double              old_theta  = theta_0;
    while (crossings.size() < 5 && dem.time() < 3 * period)
      {
        dem.step();
        const dem::Grain<3> grain = dem.gather_grains()[0];
        const double        now   = theta(grain.center);
        if ((old_theta > 0) != (now > 0))
          {
            crossings.push_back(dem.time() -
                                dem.time_step() * now / (now - old_theta));
            // At the bottom: rolling without slip.
            worst_slip = std::max(worst_slip,
                                  std::abs(grain.angular_velocity.norm() * r /
                                             grain.velocity.norm() -
                                           1));
          }
        old_theta = now;
      }
    AssertThrow(crossings.size() == 5, ExcInternalError());
    const double first  = (crossings[2] - crossings[0]) / period - 1;
    const double second = (crossings[4] - crossings[2]) / period - 1;
    deallog << "pendulum: periods / rolling period - 1 = "
            << std::setprecision(3) << first << ", " << second
            << std::setprecision(6) << "  within 0.5%: "
            << (std::abs(first) < 5e-3 && std::abs(second) < 5e-3 ? "yes" :
                                                                    "NO")
            << std::endl;
    deallog << "pendulum: |w| R / |v| at the bottom within 1% of 1: "
            << (worst_slip < 1e-2 ? "yes" : "NO") << std::endl;
  }
}
