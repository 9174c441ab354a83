// Contact histories follow grains that change rank. Two scenes cross the
// boundary between the ranks' halves of the mesh (x = 1 mm) with contacts
// that stay closed all the way, and the 2-rank run must match the 1-rank
// run to round-off:
// 1. a cohesive pair (k = 3e5 J/m^3, one grain behind the other) between
//    two plates normal to y that slide along x at 0.048 and 0.052 m/s:
//    cohesion holds the grains on both plates and together, both roll with
//    the plates, so their contact slides and its spring is loaded. The
//    front grain changes rank first (its new owner evaluates the pair for
//    the first time), then the other;
// 2. a grain rolling down a 20 degree slope (gravity tilted onto the floor
//    z-): its floor contact's spring carries the friction that makes it
//    roll; grain-wall contacts are evaluated by the grain's owner only.
// Without the hand-over of histories (before this test) the restarted
// springs put the 2-rank run 1.8e-3 R (pair) and 2.8e-6 R (rolling grain)
// away from the 1-rank run; with it the runs agree to the last digit.

#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include "tests.h"

#include <cmath>
#include <sstream>

using namespace softsand;

namespace
{
  constexpr double radius = 5e-5;

  /// The paper's material. The rolling grain: gravity tilted 20 degrees
  /// along +x onto the floor z-. The pair: no gravity, squeezed between
  /// plates normal to y that slide along x at 0.03 and 0.07 m/s.
  dem::DEMParameters
  parameters(const bool pair)
  {
    dem::DEMParameters p;
    p.material.density        = 2650;
    p.material.youngs_modulus = 5e6;
    p.material.poisson_ratio  = 0.15;
    p.material.restitution    = 0.7;
    p.material.friction       = 0.7;
    if (pair)
      {
        // Cohesion holds each grain on both plates (at the grain-wall rest
        // overlap 0.2373 R, dem_contact_laws) and the pair together.
        p.material.cohesion_energy_density = 3e5;
        std::ostringstream plates;
        plates << "plane 0 -1e-4 0 0 1 0 velocity 0.048 0 0; plane 0 "
               << -1e-4 + 2 * (1 - 0.2373) * radius
               << " 0 0 -1 0 velocity 0.052 0 0";
        p.walls.list = plates.str();
      }
    else
      {
        p.walls.box_faces  = "z-";
        const double slope = 20 * M_PI / 180;
        p.gravity = 9.81 * Tensor<1, 3>({std::sin(slope), 0, -std::cos(slope)});
      }
    // Cohesive contacts are stiff: the adaptive step (dem/time step = 0).
    p.time_step = pair ? 0 : 0.2 * p.material.rayleigh_time(radius);
    return p;
  }

  /// Run a scene on @p comm for 0.02 s: the final grains, and the ranks
  /// owning the cells of the first grain's start and end.
  std::vector<dem::Grain<3>>
  run(const bool                             pair,
      const MPI_Comm                         comm,
      std::pair<unsigned int, unsigned int> &owners)
  {
    parallel::distributed::Triangulation<3> tria(comm);
    const Point<3> lo(0, -2e-4, -1e-4), hi(2e-3, 2e-4, 1e-4);
    GridGenerator::subdivided_hyper_rectangle(tria, {16, 1, 1}, lo, hi);
    const dem::DEMParameters p = parameters(pair);
    dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
    std::vector<dem::Grain<3>> grains;
    if (pair)
      for (unsigned int k = 0; k < 2; ++k)
        {
          // One behind the other along x, each on both plates, rolling
          // with them; the pair at its rest overlap 0.2842 R*.
          dem::Grain<3> g;
          g.radius           = radius;
          g.center           = Point<3>(0.5e-3 + k * (2 - 0.1421) * radius,
                              -1e-4 + (1 - 0.2373) * radius,
                              0);
          g.velocity         = Tensor<1, 3>({0.05, 0, 0});
          g.angular_velocity = Tensor<1, 3>({0, 0, -0.002 / radius});
          grains.push_back(g);
        }
    else
      {
        // Rolling down the slope at 0.02 m/s.
        dem::Grain<3> g;
        g.radius           = radius;
        g.center           = Point<3>(0.5e-3, 0, -1e-4 + radius);
        g.velocity         = Tensor<1, 3>({0.02, 0, 0});
        g.angular_velocity = Tensor<1, 3>({0, 0.02 / radius, 0});
        grains.push_back(g);
      }
    dem.insert(grains, true);
    dem.initialize();
    while (dem.time() < 0.02)
      dem.step();
    const auto final_grains = dem.gather_grains();
    AssertThrow(final_grains.size() == grains.size(), ExcMessage("grain lost"));

    const auto owner = [&](const Point<3> &x) {
      unsigned int mine = 0;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->point_inside(x))
          mine = Utilities::MPI::this_mpi_process(comm) + 1;
      return Utilities::MPI::max(mine, comm) - 1;
    };
    owners = {owner(grains[0].center), owner(final_grains[0].center)};
    return final_grains;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  for (const bool pair : {true, false})
    {
      std::pair<unsigned int, unsigned int> owners, serial_owners;
      const auto parallel = run(pair, MPI_COMM_WORLD, owners);
      if (!root)
        continue;
      const auto serial = run(pair, MPI_COMM_SELF, serial_owners);
      double     dx = 0, dv = 0, dw = 0, travel = 0;
      for (unsigned int k = 0; k < serial.size(); ++k)
        {
          dx = std::max(dx, serial[k].center.distance(parallel[k].center));
          dv = std::max(dv,
                        (serial[k].velocity - parallel[k].velocity).norm() /
                          serial[k].velocity.norm());
          dw = std::max(
            dw,
            (serial[k].angular_velocity - parallel[k].angular_velocity).norm() /
              serial[k].angular_velocity.norm());
          travel = serial[k].center[0] - 0.5e-3;
        }
      deallog << (pair ? "sheared pair " : "rolling grain") << ": from rank "
              << owners.first << " to rank " << owners.second << ", travel "
              << std::setprecision(2) << travel / radius << " R"
              << std::setprecision(6) << std::endl;
      deallog << (pair ? "sheared pair " : "rolling grain")
              << ": 2 ranks vs 1: positions within 1e-10 R: "
              << (dx < 1e-10 * radius ? "yes" : "NO")
              << ", velocities within 1e-9: " << (dv < 1e-9 ? "yes" : "NO")
              << ", spins within 1e-9: " << (dw < 1e-9 ? "yes" : "NO")
              << std::endl;
    }
}
