// Bad input stops with a message that names the entry, the value and what
// is allowed: unknown entries, imposed fluxes that do not balance, wrong
// types, out-of-range values, missing files, overlapping grains, grains
// outside the domain, radius <= 0, a cylindrical domain that is not one or
// conditions on faces it lacks; and for granular scenes also a time step
// above the Rayleigh limit, servo walls without a target, malformed walls
// or size distributions, a wall cohesion that is negative or not a number
// and grains starting inside a wall; for coupled scenes a restart without
// checkpoint, a zero re-adaptation distance and DEM sub-steps longer than
// the stable DEM step.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/run_parameter_file.h>

#include <fstream>

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
      std::string message = softsand::base::error_message(e);
      // Paths differ between machines: keep the file name only.
      const std::string source = SOURCE_DIR;
      for (auto k = message.find(source); k != std::string::npos;
           k      = message.find(source))
        message.replace(k, source.size(), "<tests>");
      deallog << what << ": " << message << std::endl;
    }
}

/// The same for a granular (DEM-only) scene in a 1 mm box.
void
check_granular(const std::string &what, const std::string &prm_text)
{
  const std::string base =
    "subsection simulation control\n set mode = granular\n"
    " set end time = 1e-4\nend\n"
    "subsection mesh\n set lower corner = 0, 0, 0\n"
    " set upper corner = 1e-3, 1e-3, 1e-3\nend\n";
  try
    {
      run_granular_scene(base + prm_text +
                         "subsection output\n set directory = results\n"
                         " set write vtu = false\n set verbosity = quiet\nend\n");
      deallog << "granular, " << what << ": accepted (wrong)" << std::endl;
    }
  catch (const std::exception &e)
    {
      deallog << "granular, " << what << ": "
              << softsand::base::error_message(e) << std::endl;
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
  check("negative grad-div",
        "subsection fluid solver\n set grad div = -0.05\nend\n");
  // Imposed fluxes that do not balance, no pressure face (issue 55):
  // outflow 3x inflow, and a Poiseuille inflow against a uniform outflow
  // of the same peak velocity.
  check("unbalanced flow rates",
        "subsection boundary conditions\n"
        " subsection x min\n  set type = flow rate\n  set flow rate = 1e-9\n"
        " end\n subsection x max\n  set type = flow rate\n"
        "  set flow rate = -3e-9\n end\nend\n");
  check("unbalanced function inflow",
        "subsection boundary conditions\n"
        " subsection x min\n  set type = function\n"
        "  set function = 1e-3 * 16 * y * (1e-3 - y) * z * (1e-3 - z) / 1e-12; 0; 0\n"
        " end\n subsection x max\n  set type = velocity\n"
        "  set velocity = 1e-3, 0, 0\n end\nend\n");
  check("cylinder with a rectangular cross-section",
        "subsection mesh\n set geometry = cylinder\n"
        " set upper corner = 1e-3, 2e-3, 1e-3\nend\n");
  check("cylinder with coarse cells",
        "subsection mesh\n set geometry = cylinder\n"
        " set coarse cells = 2, 2, 2\nend\n");
  check("condition on a face a cylinder does not have",
        "subsection mesh\n set geometry = cylinder\nend\n"
        "subsection boundary conditions\n subsection x min\n"
        "  set type = pressure\n end\nend\n");

  {
    std::ofstream pack("overlapping_pack.txt");
    pack << "5e-4 5e-4 5e-4 1e-4\n6.5e-4 5e-4 5e-4 1e-4\n";
  }
  check_granular("overlapping grains in a loaded pack",
                 "subsection grains\n set source = file\n"
                 " set file = overlapping_pack.txt\nend\n");
  check_granular("grain outside the domain",
                 grains + " set list = 5e-4, 5e-4, 2e-3, 1e-4\nend\n");
  // Grains starting inside a wall (issue 55): through a plate, and in an
  // inlet's cylinder wall that keeps grains out.
  check_granular("grain through a plate",
                 grains + " set list = 5e-4, 5e-4, 5e-4, 1e-4; "
                 "5e-4, 5e-4, 3e-5, 1e-4\nend\n"
                 "subsection dem\n subsection walls\n  set box = z-, z+\n"
                 " end\nend\n");
  check_granular("grain inside an inlet's wall",
                 grains + " set list = 5e-4, 5e-4, 5e-4, 1e-4\nend\n"
                 "subsection dem\n subsection walls\n"
                 "  set list = cylinder 5e-4 5e-4 0 0 0 1 2e-4 outside\n"
                 " end\nend\n");
  check_granular("time step above the limit",
                 grains + " set list = 5e-4, 5e-4, 5e-4, 5e-5\nend\n"
                 "subsection dem\n set time step = 1e-5\nend\n");
  check_granular("radius <= 0",
                 grains + " set list = 5e-4, 5e-4, 5e-4, -1e-4\nend\n");
  check_granular("empty size range",
                 "subsection grains\n set source = random\n set count = 10\n"
                 " set size distribution = truncated normal\n"
                 " set mean diameter = 1e-4\n set diameter standard deviation = 2e-5\n"
                 " set min diameter = 1.2e-4\n set max diameter = 1.1e-4\nend\n");
  check_granular("servo wall without a target",
                 "subsection dem\n subsection walls\n"
                 "  set list = plane 0 1e-3 0 0 -1 0 servo\n end\nend\n");
  check_granular("unknown wall motion",
                 "subsection dem\n subsection walls\n"
                 "  set list = plane 0 0 0 0 0 1 wobble\n end\nend\n");
  check_granular("discrete sizes without fractions",
                 "subsection grains\n set source = random\n set count = 10\n"
                 " set size distribution = discrete\n"
                 " set discrete diameters = 1e-4, 2e-4\n"
                 " set discrete fractions = 1\nend\n");
  check_granular("negative wall cohesion",
                 grains + " set list = 5e-4, 5e-4, 5e-4, 1e-4\nend\n"
                 "subsection dem\n subsection material\n"
                 "  set wall cohesion energy density = -1e5\n end\nend\n");
  check_granular("wall cohesion that is not a number",
                 grains + " set list = 5e-4, 5e-4, 5e-4, 1e-4\nend\n"
                 "subsection dem\n subsection material\n"
                 "  set wall cohesion energy density = 3e5 J/m^3\n end\nend\n");
  // Coupled (CFD-DEM) scenes: a sphere in a 2 mm box.
  const std::string coupled =
    "subsection simulation control\n set mode = coupled\n"
    " set time step = 1e-3\n set end time = 1e-3\n";
  const std::string coupled_rest =
    "end\nsubsection mesh\n set lower corner = -1e-3, -1e-3, -1e-3\n"
    " set upper corner = 1e-3, 1e-3, 1e-3\n set cells per diameter = 2\nend\n"
    "subsection grains\n set source = list\n set list = 0, 0, 0, 2.5e-4\nend\n";
  check("coupled: restart without a checkpoint",
        coupled + " set restart = true\n" + coupled_rest);
  check("coupled: readapt fraction 0",
        coupled + coupled_rest +
          "subsection coupling\n set readapt fraction = 0\nend\n");
  check("coupled: DEM sub-steps above the stable step",
        coupled + coupled_rest +
          "subsection coupling\n set dem substeps = 1\nend\n");
  try
    {
      softsand::drivers::run_parameter_file("no_such_file.prm", MPI_COMM_WORLD);
    }
  catch (const std::exception &e)
    {
      deallog << "missing parameter file: "
              << softsand::base::error_message(e) << std::endl;
    }
}
