// A mesh too large for the machine is refused before it is built, with the
// entry that makes it so, the estimate and the machine's memory (masked
// here: it differs between machines). Without the check, coarse cells =
// 2000, 2000, 2000, 12 global refinements or cells per diameter = 256 (27
// grains of 1 mm: terabytes by the low estimate) grew until the machine ran
// out of memory. The parameters/drag_sphere.prm scene (2288 cells, 70416
// DoFs) still runs.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/scene_setup.h>

#include <regex>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  const std::string sphere =
    "set dimension = 3\n"
    "subsection simulation control\n set mode = steady stokes\nend\n"
    "subsection mesh\n set lower corner = -5e-3, -5e-3, -5e-3\n"
    " set upper corner = 5e-3, 5e-3, 5e-3\nend\n"
    "subsection grains\n set source = list\n set list = 0, 0, 0, 5e-4\nend\n"
    "subsection boundary conditions\n subsection x min\n"
    "  set type = velocity\n  set velocity = 1e-4, 0, 0\n end\n"
    " subsection x max\n  set type = pressure\n end\nend\n"
    "subsection output\n set directory = results\n set write vtu = false\n"
    " set verbosity = quiet\nend\n";

  void
  check(const std::string &what, const std::string &extra)
  {
    try
      {
        run_scene<3>(sphere + extra);
        deallog << what << ": ran" << std::endl;
      }
    catch (const std::exception &e)
      {
        const std::string message =
          std::regex_replace(softsand::base::error_message(e),
                             std::regex(R"(memory, [0-9.e+]+ GB)"),
                             "memory, M GB");
        deallog << what << ": " << message << std::endl;
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  check("coarse cells 2000^3",
        "subsection mesh\n set coarse cells = 2000, 2000, 2000\n"
        " set cells per diameter = 0\nend\n");
  std::ostringstream grains;
  grains << "subsection grains\n set list = ";
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        grains << (i + 1 || j + 1 || k + 1 ? "; " : "") << 2e-3 * i << ", "
               << 2e-3 * j << ", " << 2e-3 * k << ", 5e-4";
  grains << "\nend\n";
  check("27 grains, cells per diameter 256",
        grains.str() + "subsection mesh\n set cells per diameter = 256\nend\n");
  check("27 grains, cells per diameter 256, matrix free",
        grains.str() +
          "subsection mesh\n set cells per diameter = 256\nend\n"
          "subsection fluid solver\n set linear solver = matrix free\nend\n");
  check("12 global refinements",
        "subsection mesh\n set global refinements = 12\n"
        " set cells per diameter = 0\nend\n");

  // drag_sphere.prm (N = 8) passes.
  const auto row = run_scene<3>(scene_text("drag_sphere"));
  deallog << "drag_sphere.prm: ran, "
          << static_cast<unsigned int>(row.at("cells")) << " cells, "
          << static_cast<unsigned int>(row.at("dofs")) << " DoFs" << std::endl;
}
