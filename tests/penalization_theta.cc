// The paper's penalization (Eq. 6, cell-average void fraction) on the fixed
// sphere of parameters/drag_sphere.prm at 4 cells per diameter: the drag
// converges as Theta grows (1e2 -> 1e10) and the FGMRES iteration count of
// the block preconditioner (Cahouet-Chabard Schur approximation) stays
// bounded.

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
  base << scene_text("drag_sphere")
       << "subsection mesh\n set cells per diameter = 4\nend\n"
          "subsection fluid\n set solid model = penalization\nend\n";
  double       previous       = 0;
  unsigned int max_iterations = 0;
  for (const double theta : {1e2, 1e4, 1e6, 1e8, 1e10})
    {
      std::ostringstream text;
      text << base.str() << "subsection fluid\n set theta = " << theta
           << "\nend\n";
      const auto   r     = run_scene<3>(text.str());
      const double ratio = r.at("stokes_drag_ratio");
      max_iterations =
        std::max(max_iterations,
                 static_cast<unsigned int>(r.at("linear_iterations")));
      deallog << "Theta " << std::scientific << std::setprecision(0) << theta
              << std::fixed << " F/(3 pi mu d U) " << std::setprecision(4)
              << ratio;
      if (previous > 0)
        deallog << " change " << std::setprecision(4)
                << std::abs(ratio / previous - 1);
      deallog << std::setprecision(6) << std::endl;
      previous = ratio;
    }
  deallog << "FGMRES iterations per solve <= 100: "
          << (max_iterations <= 100 ? "yes" : "no") << std::endl;
}
