// Grains at rest in contact under a transient coupled fluid: one grain on
// the floor of a closed box of glycerol-like liquid, and two grains stacked
// on it (grain-grain contact). The grains' rigid velocity conflicts there
// with the wall's no-slip condition and with the other grain's; before the
// contact cells were left to the fluid and the reaction taken by rows, the
// penalty turned the DEM's contact jitter into a fluid force of about
// 3,000 weights (0.026 N) and spins growing 40x per step, and the run
// ended in NaN. Checked over 6 steps (dt = 1e-4 s, BDF2): the fastest grain
// stays below 1 mm/s, the lower grain spins below 1 rad/s, and the fluid
// force on the grains below 10 net weights (the fluid carries no
// hydrostatic pressure; buoyancy is added to the grains separately).
// Penalization and rigid nodes. Without the contact cells left to the
// fluid, or with the transient response estimate in place of the measured
// secant, the 1-grain case fails.

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <fstream>
#include <sstream>
#include <vector>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  double
  largest(const std::map<std::string, std::vector<double>> &columns,
          const std::string                                 &name)
  {
    double m = 0;
    for (const double v : columns.at(name))
      m = std::max(m, std::abs(v));
    return m;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const double r = 5e-4;
  const double net_weight =
    (2650. - 1000.) * 9.81 * 4. / 3. * M_PI * r * r * r;
  for (const std::string model : {"penalization", "rigid nodes"})
    for (const unsigned int n_grains : {1u, 2u})
      {
        if (model == "rigid nodes" && n_grains == 1)
          continue;
        const std::string list =
          n_grains == 1 ? "1.1e-3, 1.1e-3, 5e-4, 5e-4" :
                          "1.1e-3, 1.1e-3, 5e-4, 5e-4; "
                          "1.1e-3, 1.1e-3, 1.5e-3, 5e-4";
        run_scene<3>(
          "set dimension = 3\n"
          "subsection simulation control\n set mode = coupled\n"
          " set time scheme = BDF2\n set time step = 1e-4\n"
          " set end time = 6e-4\nend\n"
          "subsection mesh\n set lower corner = 0, 0, 0\n"
          " set upper corner = 2.2e-3, 2.2e-3, 2.2e-3\n"
          " set cells per diameter = 4\nend\n"
          "subsection grains\n set source = list\n set list = " +
          list +
          "\nend\n"
          "subsection dem\n set gravity = 0, 0, -9.81\n"
          " subsection material\n  set density = 2650\n"
          "  set youngs modulus = 5e6\n  set poisson ratio = 0.15\n end\n"
          " subsection walls\n  set box = all\n end\nend\n"
          "subsection fluid\n set density = 1000\n set viscosity = 1\n"
          " set theta = 1e6\n set solid model = " +
          model +
          "\nend\n"
          "subsection fluid solver\n set linear tolerance = 1e-6\nend\n"
          "subsection output\n set directory = results\n"
          " set write vtu = false\n set verbosity = quiet\nend\n");
        const auto   s     = read_statistics("results/statistics.txt");
        const double force = std::max({largest(s, "grain_force_x"),
                                       largest(s, "grain_force_y"),
                                       largest(s, "grain_force_z")});
        // The statistics carry the first grain's state: the one touching
        // the floor (and the other grain).
        double spin = 0;
        for (const std::string c : {"wx", "wy", "wz"})
          spin = std::max(spin, largest(s, "grain0_" + c));
        deallog << model << ", " << n_grains << " grain(s), " << s.at("time").size()
                << " steps: fastest grain below 1 mm/s: "
                << (largest(s, "max_speed") < 1e-3 ? "yes" : "no")
                << ", spin below 1 rad/s: " << (spin < 1 ? "yes" : "no")
                << ", fluid force below 10 net weights: "
                << (force < 10 * n_grains * net_weight ? "yes" : "no")
                << std::endl;
      }
}
