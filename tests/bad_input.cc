// Bad input stops with a message that names the entry, the value and what
// is allowed: unknown entries, wrong types, out-of-range values, missing
// files, overlapping grains, grains outside the domain, radius <= 0.

#include <deal.II/base/mpi.h>

#include <softsand/core/parameter_tools.h>

#include "test_scenes.h"
#include "tests.h"

void
check(const std::string &what, const std::string &prm_text)
{
  try
    {
      run_scene<3>(prm_text +
                   "subsection output\n set directory = results\n"
                   " set write vtu = false\n set verbosity = quiet\nend\n");
      deallog << what << ": accepted (wrong)" << std::endl;
    }
  catch (const std::exception &e)
    {
      std::string message = softsand::core::error_message(e);
      // Paths differ between machines: keep the file name only.
      const std::string source = SOURCE_DIR;
      for (auto k = message.find(source); k != std::string::npos;
           k      = message.find(source))
        message.replace(k, source.size(), "<tests>");
      deallog << what << ": " << message << std::endl;
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::string grains = "subsection grains\n set source = list\n";
  check("unknown entry", "subsection fluid\n set viscousity = 1\nend\n");
  check("wrong type", "subsection fluid\n set density = water\nend\n");
  check("out of range", "subsection fluid\n set theta = -1\nend\n");
  check("zero viscosity", "subsection fluid\n set viscosity = 0\nend\n");
  check("bad selection",
        "subsection simulation control\n set mode = steady\nend\n");
  check("inverted box", "subsection mesh\n set upper corner = 1, 1, -1\nend\n");
  check("overlapping grains",
        grains + " set list = 5e-4, 5e-4, 5e-4, 1e-4; 6e-4, 5e-4, 5e-4, 1e-4\nend\n");
  check("grain outside the domain",
        grains + " set list = 5e-4, 5e-4, 2e-3, 1e-4\nend\n");
  check("radius <= 0", grains + " set list = 5e-4, 5e-4, 5e-4, 0\nend\n");
  check("missing pack file",
        "subsection grains\n set source = file\n set file = no_such_pack.txt\nend\n");
  check("empty size range",
        "subsection grains\n set source = random\n set size distribution = "
        "uniform\n set min diameter = 2e-4\n set max diameter = 1e-4\nend\n");
  check("bad body force", "subsection fluid\n set body force = 1; x +\nend\n");
  try
    {
      softsand::core::run_parameter_file("no_such_file.prm", MPI_COMM_WORLD);
    }
  catch (const std::exception &e)
    {
      deallog << "missing parameter file: "
              << softsand::core::error_message(e) << std::endl;
    }
}
