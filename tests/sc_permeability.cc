// Permeability of a simple-cubic array at solid fraction 0.216
// (parameters/sc_permeability.prm, rigid-node grains, 4 and 8 cells per
// diameter) against Zick & Homsy (1982): K = mu U s / dp with
// dp = 6 pi mu a K* U / s^2, K* = 7.442. Also the momentum balance: the
// pressure drop over one period times the cell face equals the drag of
// one sphere, averaged over the 5 spheres (inlet and outlet cells
// included, so about 1.05 rather than 1).
// Then the paper's penalization (Theta 1e6) at 8 cells per diameter with
// the cell-average void fraction, whose cut cells are all solid and whose
// Q2 face nodes put the no-slip surface half a cell outside the grain (K a
// third of Zick-Homsy), and with the cell-majority rule (within 10 %).

#include <deal.II/base/mpi.h>

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
  std::stringstream base;
  base << scene_text("sc_permeability");
  const double s = 2e-4, mu = 1e-3, U = 1e-4, c = 0.216;
  const double a       = s * std::cbrt(3 * c / (4 * M_PI));
  const double dp_ref  = 6 * M_PI * mu * a * 7.442 * U / (s * s);
  const double k_ref   = mu * U * s / dp_ref;
  // The array of this solid fraction at @p n cells per diameter, plus @p extra.
  const auto scene = [&](const unsigned int n, const std::string &extra) {
    std::ostringstream text;
    text << base.str() << "subsection grains\n set diameter = "
         << std::setprecision(10) << 2 * a
         << "\nend\nsubsection mesh\n set cells per diameter = " << n
         << "\nend\n"
         << extra;
    return run_scene<3>(text.str());
  };
  for (const unsigned int n : {4u, 8u})
    {
      const auto r = scene(n, "");
      deallog << "N = " << n << ": K / K_Zick-Homsy = " << std::setprecision(2)
              << r.at("permeability") / k_ref
              << ", mean grain drag / (dp s^2) = "
              << r.at("grain_force_x") / 5 /
                   (r.at("pressure_drop") * s * s)
              << std::setprecision(6) << std::endl;
    }
  for (const std::string model : {"cell average", "cell majority"})
    {
      const auto r = scene(
        8,
        "subsection fluid\n set solid model = penalization\nend\n"
        "subsection fluid solver\n set schur complement = discrete "
        "brinkman\nend\n"
        "subsection coupling\n set void fraction model = " +
          model + "\nend\n");
      deallog << "penalization, " << model
              << ", N = 8: K / K_Zick-Homsy = " << std::setprecision(2)
              << r.at("permeability") / k_ref << std::setprecision(6)
              << std::endl;
    }
}
