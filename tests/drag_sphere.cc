// A fixed sphere in a uniform stream at Re = 0.1 (parameters/drag_sphere.prm
// at 4 cells per diameter): the drag from the penalization reaction over
// 3 pi mu d U (above 1 in a 10-diameter box), the paper's Eq. (7) estimate,
// and the momentum balance (fluid force on the grain against the force on
// the box). Run on 2 ranks, then on 1 rank: the two drags must agree to
// 1e-6 relative.

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
  std::stringstream text;
  text << scene_text("drag_sphere")
       << "subsection mesh\n set cells per diameter = 4\nend\n"
       << "subsection postprocessing\n set eq7 forces = true\nend\n";

  const auto parallel = run_scene<3>(text.str(), MPI_COMM_WORLD);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  deallog << "ranks " << n_ranks << std::endl;
  deallog << "F / (3 pi mu d U) = " << std::setprecision(4)
          << parallel.at("stokes_drag_ratio") << std::endl;
  deallog << "Eq. 7 F / (3 pi mu d U) = " << std::setprecision(2)
          << parallel.at("eq7_stokes_drag_ratio") << std::endl;
  deallog << "grain force / box force = " << std::setprecision(2)
          << parallel.at("grain_force_x") / parallel.at("boundary_force_x")
          << std::endl;
  deallog << "Re = " << parallel.at("reynolds_number") << std::endl;

  if (n_ranks > 1)
    {
      MPI_Comm self = MPI_COMM_SELF;
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          const auto   serial = run_scene<3>(text.str(), self);
          const double diff =
            std::abs(serial.at("stokes_drag_ratio") /
                       parallel.at("stokes_drag_ratio") -
                     1.);
          deallog << "1 vs " << n_ranks
                  << " ranks: relative drag difference below 1e-6: "
                  << (diff < 1e-6 ? "yes" : "no") << std::endl;
        }
      MPI_Barrier(MPI_COMM_WORLD);
    }
}
