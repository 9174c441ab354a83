// Step rate of the DEM contact loop on a settling pack: 6,750 grains
// (R = 0.0485-0.05 mm, the paper's material, 2650 kg/m^3) on a touching
// 15 x 15 x 30 lattice with random velocities of up to 0.05 m/s, falling
// onto the floor of a closed box under gravity; one rank, dt = 0.2 T_R.
// After 15,000 steps the coordination is 3.5. Not a test (no .output):
// build it against two checkouts to compare them, e.g. with
//   add_executable(dem_step_rate tests/tools/dem_step_rate.cc
//     source/dem/granular_dynamics.cc source/dem/contact_law.cc
//     source/dem/walls.cc source/dem/material.cc source/dem/dem_parameters.cc
//     source/dem/grain_parameters.cc source/dem/pack_generators.cc
//     source/base/parameter_tools.cc)
//   (granular_dynamics.cc with -O3, as in the main CMakeLists.txt), then
//   ./dem_step_rate 15000

#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>

#include <softsand/dem/granular_dynamics.h>

#include <iostream>
#include <random>

using namespace dealii;
using namespace softsand;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     r = 5e-5;
  dem::DEMParameters               p;
  p.material.density        = 2650;
  p.material.youngs_modulus = 5e6;
  p.material.poisson_ratio  = 0.15;
  p.material.restitution    = 0.7;
  p.material.friction       = 0.7;
  p.time_step               = 0.2 * p.material.rayleigh_time(r);
  p.gravity                 = Tensor<1, 3>({0, 0, -9.81});
  p.walls.box_faces         = "all";
  parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
  const Point<3> lo(0, 0, 0), hi(1.6e-3, 1.6e-3, 3.2e-3);
  GridGenerator::subdivided_hyper_rectangle(tria, {12, 12, 24}, lo, hi);
  dem::GranularDynamics dem(tria, p, BoundingBox<3>(std::make_pair(lo, hi)));
  std::vector<dem::Grain<3>>             grains;
  std::mt19937                           rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (unsigned int k = 0; k < 30; ++k)
    for (unsigned int j = 0; j < 15; ++j)
      for (unsigned int i = 0; i < 15; ++i)
        {
          dem::Grain<3> g;
          g.radius = r * (0.97 + 0.03 * u(rng));
          g.center = Point<3>(1e-4 * (i + 1), 1e-4 * (j + 1), 1e-4 * (k + 1));
          g.velocity =
            Tensor<1, 3>({0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng)});
          grains.push_back(g);
        }
  dem.insert(grains, true);
  dem.initialize();
  const unsigned int n = argc > 1 ? std::atoi(argv[1]) : 15000;
  Timer              timer;
  for (unsigned int s = 0; s < n; ++s)
    dem.step();
  const double seconds = timer.wall_time();
  const auto   statistics =
    dem.statistics(BoundingBox<3>(std::make_pair(lo, hi)));
  std::cout << grains.size() << " grains, " << n << " steps in " << seconds
            << " s: " << grains.size() * n / seconds
            << " grain-steps/s, coordination " << statistics.coordination
            << std::endl;
}
