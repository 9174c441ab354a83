// The pressure regions' constraints agree between ranks. On the small
// Hele-Shaw cell at 4 cells per mean diameter the inlet reservoir holds a
// hanging face whose coarse side belongs to one rank and fine side to the
// other: each rank decided alone which reservoir velocity nodes are fixed,
// the two disagreed, and the first coupled step returned velocities of
// 1e5 m/s in the inlet (largest cell pore Reynolds number 5.8e6, against
// 11 at the 95th percentile), which the next step's Courant limit then
// cut to 1/1024 of the step and the grains' forces blew up. Checked on 2
// ranks: the largest and the 95th-percentile pore Reynolds numbers of the
// first step and its radial flow rate.

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const auto r = run_scene<3>(
    scene_text("hele_shaw_small") +
    "subsection simulation control\n set max time steps = 1\nend\n"
    "subsection mesh\n set cells per diameter = 2.66\nend\n"
    "subsection boundary conditions\n subsection inlet region\n"
    "  set pressure = 8000\n end\nend\n"
    "subsection grains\n set file = " + std::string(SOURCE_DIR) +
    "/../parameters/packs/hele_shaw_small.txt\nend\n");

  const double re_max = r.at("pore_reynolds_max");
  const double re_p95 = r.at("pore_reynolds_p95");
  deallog << "DoFs " << static_cast<long>(r.at("dofs")) << std::endl;
  deallog << "pore Reynolds number: 95th percentile " << std::setprecision(3)
          << re_p95 << ", largest below 20 times it: "
          << (re_max < 20 * re_p95 ? "yes" : "NO") << std::endl;
  deallog << "radial flow rate " << std::scientific << std::setprecision(3)
          << r.at("radial_flow_rate") << " m^3/s" << std::endl;
}
