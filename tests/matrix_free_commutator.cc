// The matrix-free solver path with the least-squares-commutator Schur block
// (linear solver = matrix free, p-multigrid Q2 -> Q1 with AMG on the
// assembled Q1 operator) against the matrix-based default, on the three
// kinds of dense-pack systems: one sphere penalized with Theta = 1e12
// (drag), a simple-cubic array of rigid-node grains with the pressure
// smoothing (permeability), and the small Hele-Shaw cell (250 rigid-node
// grains, inlet and perimeter pressure regions; radial permeability). Both
// paths discretize the same system, so the quantities agree to the solver
// tolerance; the matrix-free one takes a bounded number of FGMRES
// iterations.

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  std::string
  with_solver(const std::string &scene, const std::string &linear_solver)
  {
    return scene + "subsection fluid solver\n set linear solver = " +
           linear_solver +
           "\n set linear tolerance = 1e-8\n"
           " set schur complement = least squares commutator\nend\n";
  }

  void
  compare(const std::string  &name,
          const std::string  &scene,
          const std::string  &quantity,
          const unsigned int  max_iterations)
  {
    const auto mb = run_scene<3>(with_solver(scene, "matrix based"));
    const auto mf = run_scene<3>(with_solver(scene, "matrix free"));
    const double difference =
      std::abs(mf.at(quantity) / mb.at(quantity) - 1);
    deallog << name << ": " << quantity << " " << std::setprecision(4)
            << std::scientific << mf.at(quantity) << std::defaultfloat
            << std::setprecision(6)
            << ", matrix free vs matrix based within 1e-5: "
            << (difference < 1e-5 ? "yes" : "NO") << std::endl;
    deallog << name << ": matrix-free FGMRES iterations <= "
            << max_iterations << ": "
            << (mf.at("linear_iterations") <= max_iterations ? "yes" : "NO")
            << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  compare("sphere, Theta 1e12, N = 6",
          scene_text("drag_sphere") +
            "subsection mesh\n set cells per diameter = 6\nend\n"
            "subsection fluid\n set solid model = penalization\n"
            " set theta = 1e12\nend\n",
          "grain_force_x",
          60);
  compare("simple-cubic array c = 0.216, rigid nodes, N = 4",
          scene_text("sc_permeability"),
          "permeability",
          40);
  compare("small Hele-Shaw cell, first coupled step",
          scene_text("hele_shaw_small") +
            "subsection simulation control\n set max time steps = 1\n"
            " set time step = 1e-3\nend\n"
            "subsection coupling\n set fluid model = quasi-steady\nend\n"
            "subsection grains\n set file = " + std::string(SOURCE_DIR) +
            "/../parameters/packs/hele_shaw_small.txt\nend\n",
          "radial_permeability",
          40);
}
