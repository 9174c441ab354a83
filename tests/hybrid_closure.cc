// The hybrid model's porous zone (coupling/porous_zone.h).
// 1. A simple-cubic array at solid fraction 0.216 (parameters/
//    sc_permeability.prm) with every grain porous (resolved radius 0):
//    each cell's averaging box spans one lattice period, so the porosity
//    is the array's, 0.784, and the permeability between the pressure-drop
//    planes is the closure's, K = phi^3 d^2 / (A (1 - phi)^2), for two
//    values of A (Darcy's law: K / K_closure = 1 for both). The grains then
//    carry the whole pressure drop: the force on each inner grain is
//    dp s^2, dp the drop over one period (the end grains' boxes are
//    clipped by the domain, so the mean over all five is not 1). The
//    resolved array (rigid nodes, 4 cells per d) beside it against Zick &
//    Homsy.
// 2. The hand-over at the zone's surface: the porous share of a grain
//    whose centre lies at R + t r (0 at t = -1, 1/2 at 0, 1 at 1, and
//    share(t) + share(-t) = 1).

#include <deal.II/base/mpi.h>

#include <softsand/coupling/porous_zone.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const double s = 2e-4, mu = 1e-3, c = 0.216;
  const double a   = s * std::cbrt(3 * c / (4 * M_PI));
  const double d   = 2 * a;
  const double phi = 1 - c;
  const double k_zick_homsy = s * s * s / (6 * M_PI * a * 7.442);
  const auto   scene = [&](const std::string &extra) {
    std::ostringstream text;
    text << scene_text("sc_permeability") << "subsection grains\n set diameter = "
         << std::setprecision(10) << d << "\nend\n"
         << extra;
    return run_scene<3>(text.str());
  };

  const auto resolved =
    scene("subsection mesh\n set cells per diameter = 4\nend\n");
  deallog << "resolved (rigid nodes, 4 cells per d): K / K_Zick-Homsy = "
          << std::setprecision(3)
          << resolved.at("permeability") / k_zick_homsy << std::endl;

  // Cells 0.05 mm long and one period across, their boxes grown by
  // (s - 0.05 mm) / 2 on each side: one period in every direction.
  const double width = (s - 5e-5) / 2 / d;
  for (const double A : {180., 60.})
    {
      std::ostringstream extra;
      extra << std::setprecision(10)
            << "subsection mesh\n set coarse cells = 20, 1, 1\n"
               " set cells per diameter = 4\nend\n"
               "subsection coupling\n subsection hybrid model\n"
               "  set resolved radius = 0\n  set kozeny constant = "
            << A << "\n  set averaging width = " << width << "\n end\nend\n";
      const auto   r = scene(extra.str());
      // The three inner grains (away from the clipped end boxes).
      std::ifstream forces("results/grain_forces.txt");
      std::string   line;
      double        inner = 0;
      while (std::getline(forces, line))
        if (!line.empty() && line[0] != '#')
          {
            std::istringstream row(line);
            unsigned int       g;
            double x, y, z, radius, fx;
            row >> g >> x >> y >> z >> radius >> fx;
            if (g >= 1 && g <= 3)
              inner += fx / 3;
          }
      const double k_closure =
        phi * phi * phi * d * d / (A * (1 - phi) * (1 - phi));
      deallog << "porous, A = " << A << ": K / K_closure = "
              << std::setprecision(4) << r.at("permeability") / k_closure
              << ", K / K_Zick-Homsy = " << std::setprecision(3)
              << r.at("permeability") / k_zick_homsy
              << ", grain force / (dp s^2): mean " << std::setprecision(3)
              << r.at("grain_force_x") / 5 / (r.at("pressure_drop") * s * s)
              << ", inner three " << std::setprecision(4)
              << inner / (r.at("pressure_drop") * s * s)
              << ", cells " << r.at("cells") << std::endl;
    }

  // The hand-over share and a box's porosity, without a fluid.
  using namespace softsand;
  std::vector<dem::Grain<3>> grains(1);
  grains[0].radius = a;
  const double                    R = 1e-3;
  coupling::HybridModelParameters hybrid;
  hybrid.enabled         = true;
  hybrid.resolved_radius = R;
  const BoundingBox<3> domain(
    std::make_pair(Point<3>(-1, -1, -1), Point<3>(1, 1, 1)));
  for (const double t : {-1., -0.5, 0., 0.5, 1.})
    {
      grains[0].center = Point<3>(R + t * a, 0, 0);
      const coupling::GrainLocator<3> locator(grains);
      const coupling::PorousZone<3>   zone(
        grains, locator, hybrid, Point<3>(), Tensor<1, 3>({0, 0, 1}), domain);
      deallog << "centre at R + " << t
              << " r: porous share = " << std::setprecision(5)
              << zone.porous_share(grains[0]) << std::endl;
    }
  return 0;
}
