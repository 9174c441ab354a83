// The octagon of 8 servo pistons between two plates (walls/octagon).
//
// 1. One grain (R = 0.05 mm, the paper's material) at the centre of an
//    octagon of inradius 0.1 mm, pistons driven to 5 kPa: each piston must
//    come to rest where its Hertz force equals the target load,
//    delta = (3 p A / (4 Y* sqrt(R)))^(2/3) with A = 2 r_oct tan(pi/8) h,
//    the same for all 8 (measured from the grain's final centre and each
//    plane, i.e. the exact geometry). The proportional servo settles
//    exactly there: measured 1e-13 relative.
// 2. parameters/octagon_compaction.prm: 60 grains compacted to 5 kPa. The
//    pack is chaotic, so it is checked by physical bands: settled with all
//    8 pistons within 2% of the target for 10,000 steps, the octagon
//    symmetric (its 4 widths within 4% of their mean: at most 1.6% over
//    seeds 1-6), its centre within half a grain radius of the start (the
//    pack's position is neutral under equal pressures: up to 0.2 R over
//    seeds 1-6), and the grains' area fraction of the octagon that of a
//    compacted random layer of discs (0.82 measured).
// 3. The contact stress (Love-Weber, `contact_stress_*` columns). One
//    grain: sigma_xx + sigma_yy is the pistons' forces times the branch
//    lengths r - delta/2 over the probe volume, exactly. A pack in
//    equilibrium carries on average the load its boundary applies: without
//    friction (3.), (sigma_xx + sigma_yy) V is the pistons' sum of F_k R_k
//    (measured 1.004); with friction 0.7 (2.) the plates' friction takes
//    part of it (0.75 measured: the in-plane load pushes grains against
//    the plates, sigma_zz > 0).

#include <deal.II/base/mpi.h>

#include <softsand/drivers/granular_scene.h>
#include <softsand/dem/walls.h>

#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  using namespace softsand;

  /// Run a granular scene; @p check looks at the simulator afterwards.
  template <typename Check>
  void
  run(const std::string &text, const Check &check)
  {
    ParameterHandler prm;
    core::Parameters<3>::declare_parameters(prm);
    prm.parse_input_from_string(text);
    core::Parameters<3> parameters;
    parameters.parse_parameters(prm);
    drivers::GranularScene simulator(parameters, MPI_COMM_WORLD);
    simulator.run();
    check(simulator, parameters);
  }

  /// The grains' in-plane contact stress (sigma_xx + sigma_yy times the
  /// probe's volume) over the pistons' load, the sum of their normal forces
  /// times their distances from the octagon's centre (the origin): 1 for a
  /// pack in equilibrium that only the pistons load in-plane.
  double
  in_plane_stress_over_piston_load(const drivers::GranularScene &simulator,
                                   const BoundingBox<3>         &probe)
  {
    double load = 0;
    for (const auto &wall : simulator.dynamics().get_walls())
      if (wall.name.find("piston") == 0)
        load += wall.normal_force * -(wall.point * wall.normal);
    const auto stress = simulator.dynamics().statistics(probe).contact_stress;
    return (stress[0][0] + stress[1][1]) * probe.volume() / load;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // 1. One grain.
  {
    const double      r = 5e-5, h = 1.2e-4, r_oct = 1e-4, p = 5e3;
    std::stringstream text;
    text << scene_text("octagon_compaction")
         << "subsection mesh\n set lower corner = -1.5e-4, -1.5e-4, 0\n"
            " set upper corner = 1.5e-4, 1.5e-4, 1.2e-4\nend\n"
            "subsection grains\n set source = list\n set list = 0, 0, 6e-5, "
            "5e-5\nend\n"
            "subsection dem\n set gravity = 0, 0, 0\n"
            " set settled kinetic energy = 1e-24\n set settled checks = 5\n"
            " subsection walls\n  set octagon = 0, 0, 1e-4\n end\nend\n";
    run(text.str(),
        [&](const drivers::GranularScene &simulator,
            const core::Parameters<3>     &parameters) {
          const auto  &walls = simulator.dynamics().get_walls();
          const auto   grain = simulator.dynamics().gather_grains()[0];
          const double y_eff =
            parameters.dem.material.effective_youngs_modulus();
          const double area = 2 * r_oct * std::tan(M_PI / 8) * h;
          const double delta =
            std::pow(3 * p * area / (4 * y_eff * std::sqrt(r)), 2. / 3.);
          double       worst_overlap = 0, worst_pressure = 0;
          unsigned int n_pistons = 0;
          for (const auto &wall : walls)
            if (wall.name.find("piston") == 0)
              {
                ++n_pistons;
                const double overlap =
                  r - (grain.center - wall.point) * wall.normal;
                worst_overlap =
                  std::max(worst_overlap, std::abs(overlap / delta - 1));
                worst_pressure =
                  std::max(worst_pressure, std::abs(wall.pressure() / p - 1));
              }
          // The contact stress: sum of F_k (r - delta_k / 2) over the box
          // volume for sigma_xx + sigma_yy (each piston's normal in-plane).
          const BoundingBox<3> box(
            std::make_pair(Point<3>(-1.5e-4, -1.5e-4, 0),
                           Point<3>(1.5e-4, 1.5e-4, 1.2e-4)));
          double in_plane = 0;
          for (const auto &wall : walls)
            if (wall.name.find("piston") == 0)
              {
                const double overlap =
                  r - (grain.center - wall.point) * wall.normal;
                in_plane += wall.normal_force * (r - 0.5 * overlap);
              }
          in_plane /= box.volume();
          const auto stress =
            simulator.dynamics().statistics(box).contact_stress;
          deallog << "one grain: contact stress xx + yy within 1e-9 of the "
                     "pistons' forces times r - delta/2 over the volume: "
                  << (std::abs((stress[0][0] + stress[1][1]) / in_plane - 1) <
                          1e-9 ?
                        "yes" :
                        "NO")
                  << ", xx = yy within 1e-6: "
                  << (std::abs(stress[0][0] / stress[1][1] - 1) < 1e-6 ? "yes" :
                                                                         "NO")
                  << ", zz (no plate touched) 0: "
                  << (stress[2][2] == 0 ? "yes" : "NO") << std::endl;
          deallog << "one grain: settled "
                  << (simulator.results().at("settled") > 0 ? "yes" : "no")
                  << ", pistons " << n_pistons << ", Hertz overlap delta / R "
                  << std::setprecision(4) << delta / r << std::setprecision(6)
                  << std::endl;
          deallog << "one grain: every piston's overlap within 1e-6 of Hertz: "
                  << (worst_overlap < 1e-6 ? "yes" : "NO")
                  << ", pressure within 1e-6 of 5 kPa: "
                  << (worst_pressure < 1e-6 ? "yes" : "NO")
                  << ", grain stays at the centre (within 1e-6 R): "
                  << (std::hypot(grain.center[0], grain.center[1]) < 1e-6 * r ?
                        "yes" :
                        "NO")
                  << std::endl;
        });
  }

  // 2. A pack of 60 grains.
  {
    std::stringstream text;
    text << scene_text("octagon_compaction");
    run(text.str(),
        [&](const drivers::GranularScene &simulator,
            const core::Parameters<3> &) {
          const auto          &r     = simulator.results();
          const auto          &walls = simulator.dynamics().get_walls();
          const BoundingBox<3> domain(
            std::make_pair(Point<3>(-0.85e-3, -0.85e-3, 0),
                           Point<3>(0.85e-3, 0.85e-3, 0.12e-3)));
          // Inradius of each piston (distance from the octagon's centre), and
          // the octagon's area from the drawn faces: sum of inradius x side
          // / 2.
          std::vector<double> inradius;
          double              octagon_area = 0;
          for (unsigned int k = 0; k < walls.size(); ++k)
            if (walls[k].name.find("piston") == 0)
              {
                inradius.push_back(-(walls[k].point * walls[k].normal));
                const auto face = dem::plane_wall_face(walls, k, domain);
                double     side = 0;
                for (unsigned int a = 0; a < face.size(); ++a)
                  side = std::max(
                    side,
                    std::hypot(face[a][0] - face[(a + 1) % face.size()][0],
                               face[a][1] - face[(a + 1) % face.size()][1]));
                octagon_area += 0.5 * inradius.back() * side;
              }
          double mean_width = 0, widest = 0, narrowest = 1, off_centre = 0;
          for (unsigned int k = 0; k < 4; ++k)
            mean_width += 0.25 * (inradius[k] + inradius[k + 4]);
          for (unsigned int k = 0; k < 4; ++k)
            {
              const double width = (inradius[k] + inradius[k + 4]) / mean_width;
              widest             = std::max(widest, width);
              narrowest          = std::min(narrowest, width);
              off_centre =
                std::max(off_centre,
                         std::abs(inradius[k] - inradius[k + 4]) / 2);
            }
          double grain_area = 0;
          for (const auto &g : simulator.dynamics().gather_grains())
            grain_area += M_PI * g.radius * g.radius;
          const double fraction = grain_area / octagon_area;
          double       worst    = 0;
          for (unsigned int k = 0; k < 8; ++k)
            worst = std::max(
              worst,
              std::abs(r.at("piston_" + std::to_string(k) + "_pressure") / 5e3 -
                       1));
          deallog << "pack: settled with all 8 pistons within 2% of 5 kPa for "
                     "10,000 steps: "
                  << (r.at("settled") > 0 ? "yes" : "NO")
                  << ", final pressures within 0.5%: "
                  << (worst < 5e-3 ? "yes" : "NO") << ", lost grains "
                  << r.at("lost_grains") << std::endl;
          const double ratio =
            in_plane_stress_over_piston_load(simulator, domain);
          const double zz =
            simulator.dynamics().statistics(domain).contact_stress[2][2];
          deallog << "pack: in-plane contact stress over the pistons' load in "
                     "[0.6, 0.9] (the plates' friction carries the rest): "
                  << (ratio > 0.6 && ratio < 0.9 ? "yes" : "NO")
                  << ", zz > 0 (grains pushed against the plates): "
                  << (zz > 0 ? "yes" : "NO") << std::endl;
          deallog << "pack: 4 widths within 4% of their mean: "
                  << (widest < 1.04 && narrowest > 0.96 ? "yes" : "NO")
                  << ", centre within R/2 of the start: "
                  << (off_centre < 2.5e-5 ? "yes" : "NO")
                  << ", area fraction in [0.75, 0.95]: "
                  << (fraction > 0.75 && fraction < 0.95 ? "yes" : "NO")
                  << std::endl;
        });
  }

  // 3. The same pack without friction: only the pistons load it in-plane.
  {
    std::stringstream text;
    text << scene_text("octagon_compaction")
         << "subsection dem\n subsection material\n  set friction = 0\n"
            " end\nend\n";
    run(text.str(),
        [&](const drivers::GranularScene &simulator,
            const core::Parameters<3> &) {
          const BoundingBox<3> domain(
            std::make_pair(Point<3>(-0.85e-3, -0.85e-3, 0),
                           Point<3>(0.85e-3, 0.85e-3, 0.12e-3)));
          const double ratio =
            in_plane_stress_over_piston_load(simulator, domain);
          deallog << "frictionless pack: in-plane contact stress within 1% of "
                     "the pistons' load: "
                  << (std::abs(ratio - 1) < 0.01 ? "yes" : "NO") << std::endl;
        });
  }
}
