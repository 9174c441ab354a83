// Cylinder walls with the grains outside (a post; the wall of the Hele-Shaw
// inlet that keeps grains out), the axis along (1, 1, 0)/sqrt(2).
//
// 1. A frictionless elastic grain (e = 1, mu = 0, R = 0.05 mm, the paper's
//    Y and nu) hits a post of radius 1 mm obliquely (30 degrees from the
//    radial direction, with an axial component) and bounces off it. At
//    every step of the contact the force on the grain must point from the
//    axis through the grain centre (outwards) with the Hertz magnitude
//    4/3 Y* sqrt(R) delta^(3/2) of the exact overlap delta = R - (rho - R_c),
//    rho the centre's distance from the axis. The force is central about
//    the axis and normal to it, so the axial velocity and the angular
//    momentum about the axis are conserved; with e = 1 the speed comes
//    back and the radial velocity turns outwards.
// 2. 40 grains (R = 0.5 mm, mu = 0.7, e = 0.7) thrown at a post of radius
//    2 mm from all sides (0.2 m/s towards the axis, between two plates)
//    stay out of it: over 10 ms no grain centre is closer to the axis
//    than R_c + 0.9 R, and each grain left the post moving outwards or
//    rests against it.

#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include "tests.h"

#include <cmath>

using namespace softsand;

namespace
{
  const Tensor<1, 3> axis({1 / std::sqrt(2.), 1 / std::sqrt(2.), 0});
  const Tensor<1, 3> e_up({0, 0, 1});
  const Tensor<1, 3> e_side({-1 / std::sqrt(2.), 1 / std::sqrt(2.), 0});

  Tensor<1, 3>
  radial(const Point<3> &x, const Tensor<1, 3> &a)
  {
    Tensor<1, 3> d = x;
    return d - (d * a) * a;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // 1. Frictionless elastic bounce off the post.
  {
    const double       r = 5e-5, r_c = 1e-3, speed = 0.1;
    dem::DEMParameters p;
    p.material.density        = 2500;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = 1.0;
    p.material.friction       = 0.0;
    p.time_step               = 0.2 * p.material.rayleigh_time(r);
    std::ostringstream wall;
    wall << "cylinder 0 0 0 " << axis[0] << ' ' << axis[1] << ' ' << axis[2]
         << ' ' << r_c << " outside";
    p.walls.list = wall.str();
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-1.6e-3, -1.6e-3, -1.6e-3), hi(1.6e-3, 1.6e-3, 1.6e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    AssertThrow(dem.get_walls()[0].outside, ExcInternalError());
    std::vector<dem::Grain<3>> grains(1);
    grains[0].radius = r;
    // Outside the post, moving towards it at 30 degrees from the radial (it
    // would miss the post at 60).
    grains[0].center   = Point<3>(1.3e-3 * e_up + 1e-4 * axis);
    const double angle = M_PI / 6;
    grains[0].velocity =
      speed * (-std::cos(angle) * e_up + std::sin(angle) * e_side) +
      0.3 * speed * axis;
    dem.insert(grains, true);
    dem.initialize();

    const auto angular_momentum = [](const dem::Grain<3> &g) {
      return cross_product_3d(radial(g.center, axis), g.velocity) * axis;
    };
    const double y_eff       = p.material.effective_youngs_modulus();
    const double l_0         = angular_momentum(grains[0]);
    const double axial_0     = grains[0].velocity * axis;
    double       worst_angle = 0, worst_force = 0, max_overlap = 0;
    unsigned int contact_steps = 0, steps_after = 0;
    while (steps_after < 100 && dem.step_number() < 100000)
      {
        dem.step();
        const auto all = dem.gather_grains();
        if (all.empty())
          {
            deallog << "bounce: the grain left the box at step "
                    << dem.step_number() << " (contact steps " << contact_steps
                    << ")" << std::endl;
            return 1;
          }
        const dem::Grain<3> g     = all[0];
        const Tensor<1, 3>  rho   = radial(g.center, axis);
        const double        delta = r - (rho.norm() - r_c);
        // The wall's force is minus the force on the grain.
        const Tensor<1, 3> force = -dem.get_walls()[0].force;
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
    deallog << "bounce: force outwards from the axis within 1e-12: "
            << (worst_angle < 1e-12 ? "yes" : "NO")
            << ", Hertz force of the exact overlap within 1e-9: "
            << (worst_force < 1e-9 ? "yes" : "NO") << std::endl;
    deallog
      << "bounce: axial velocity kept within 1e-12: "
      << (std::abs(g.velocity * axis / axial_0 - 1) < 1e-12 ? "yes" : "NO")
      << ", angular momentum about the axis within 1e-9: "
      << (std::abs(angular_momentum(g) / l_0 - 1) < 1e-9 ? "yes" : "NO")
      << ", speed within 1e-3: "
      << (std::abs(g.velocity.norm() / grains[0].velocity.norm() - 1) < 1e-3 ?
            "yes" :
            "NO")
      << ", radial velocity outwards: "
      << (g.velocity * radial(g.center, axis) > 0 ? "yes" : "NO") << std::endl;
  }

  // 2. A ring of grains thrown at a vertical post between two plates.
  {
    const double       r = 5e-4, r_c = 2e-3, speed = 0.2;
    const Tensor<1, 3> z({0, 0, 1});
    dem::DEMParameters p;
    p.material.density        = 2650;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = 0.7;
    p.material.friction       = 0.7;
    p.walls.box_faces         = "z-, z+";
    p.walls.list              = "cylinder 0 0 0 0 0 1 2e-3 outside";
    parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
    const Point<3> lo(-6e-3, -6e-3, 0), hi(6e-3, 6e-3, 2.5e-3);
    GridGenerator::hyper_rectangle(tria, lo, hi);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    std::vector<dem::Grain<3>> grains;
    for (unsigned int k = 0; k < 40; ++k)
      {
        // Two rings (two layers), 20 grains each, 1 mm from the post.
        const double       phi = 2 * M_PI * (k % 20) / 20 + (k / 20) * 0.1;
        const Tensor<1, 3> out({std::cos(phi), std::sin(phi), 0});
        dem::Grain<3>      g;
        g.radius = r;
        g.center =
          Point<3>((r_c + r + 1e-3) * out + (k < 20 ? 0.6e-3 : 1.9e-3) * z);
        g.velocity = -speed * out;
        grains.push_back(g);
      }
    dem.insert(grains, true);
    dem.initialize();
    double closest = std::numeric_limits<double>::max();
    while (dem.time() < 1e-2)
      {
        dem.step();
        for (const auto &g : dem.gather_grains())
          closest = std::min(closest, radial(g.center, z).norm());
      }
    unsigned int leaving_or_resting = 0;
    for (const auto &g : dem.gather_grains())
      {
        const Tensor<1, 3> rho = radial(g.center, z);
        if (g.velocity * rho > 0 || rho.norm() < r_c + 1.01 * r)
          ++leaving_or_resting;
      }
    deallog << "post: closest centre to the axis at least R_c + 0.9 R: "
            << ((closest - r_c) / r > 0.9 ? "yes" : "NO") << std::endl;
    deallog << "post: every grain leaving the post or resting on it: "
            << (leaving_or_resting == grains.size() ? "yes" : "NO")
            << ", grains in the box " << dem.gather_grains().size()
            << std::endl;
  }
}
