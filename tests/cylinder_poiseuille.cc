// mesh/geometry = cylinder: Hagen-Poiseuille flow through an empty pipe of
// radius R along z (flow-rate inlet at z min, pressure outlet at z max, the
// mantle a no-slip wall) has K = q mu L / dp = R^2 / 8 (the meshed mantle is
// an inscribed 32-gon: its end has 0.994 of the circle's area); the same
// pipe along x gives the same K (the rotation). Then five grains in the
// pipe with the mesh refined around them (hanging faces next to the
// mantle): the outflow equals the inflow, the mesh conserves mass.

#include <deal.II/base/mpi.h>

#include <cmath>
#include <sstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  const double R = 2.5e-4;

  std::string
  pipe(const char axis, const std::string &extra)
  {
    const std::string lower = axis == 'z' ? "-2.5e-4, -2.5e-4, 0" :
                                            "0, -2.5e-4, -2.5e-4";
    const std::string upper = axis == 'z' ? "2.5e-4, 2.5e-4, 1e-3" :
                                            "1e-3, 2.5e-4, 2.5e-4";
    const std::string in  = axis == 'z' ? "z min" : "x min";
    const std::string out = axis == 'z' ? "z max" : "x max";
    std::ostringstream text;
    text << "set dimension = 3\n"
            "subsection simulation control\n set mode = steady stokes\nend\n"
            "subsection mesh\n set geometry = cylinder\n set cylinder axis = "
         << axis << "\n set lower corner = " << lower
         << "\n set upper corner = " << upper
         << "\n set cells per diameter = 0\nend\n"
            "subsection fluid\n set viscosity = 1e-3\nend\n"
            "subsection boundary conditions\n subsection "
         << in << "\n  set type = flow rate\n  set flow rate = "
         << std::setprecision(10) << 1e-3 * M_PI * R * R
         << "\n end\n subsection " << out
         << "\n  set type = pressure\n end\nend\n"
            "subsection postprocessing\n set flow axis = "
         << axis
         << "\n set pressure drop planes = 3e-4, 7e-4\nend\n"
            "subsection output\n set directory = results\n set write vtu = "
            "false\n set verbosity = quiet\nend\n"
         << extra;
    return text.str();
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const double k_exact = R * R / 8;
  for (const char axis : {'z', 'x'})
    {
      const auto   row  = run_scene<3>(pipe(axis, ""));
      const double area = row.at("flow_rate") / row.at("superficial_velocity");
      deallog << "empty pipe along " << axis
              << ": inlet area / (pi R^2) = " << std::setprecision(4)
              << area / (M_PI * R * R)
              << ", K / (R^2 / 8) = " << row.at("permeability") / k_exact
              << std::endl;
    }
  const auto row = run_scene<3>(pipe(
    'z',
    "subsection mesh\n set cells per diameter = 6\nend\n"
    "subsection grains\n set source = list\n set list = "
    "1.2e-4, 0, 2e-4, 8e-5; -1.2e-4, 0, 3.5e-4, 8e-5; 0, 1.2e-4, 5e-4, 8e-5; "
    "0, -1.2e-4, 6.5e-4, 8e-5; 0, 0, 8e-4, 8e-5\nend\n"
    "subsection fluid\n set solid model = penalization\n set theta = 1e6\n"
    "end\nsubsection fluid solver\n set schur complement = discrete "
    "brinkman\n set linear tolerance = 1e-10\nend\n"
    "subsection coupling\n set void fraction model = cell majority\nend\n"
    "subsection simulation control\n set time step = 1e-5\nend\n"));
  deallog << "five grains, refined around them: outflow / inflow = "
          << std::setprecision(6)
          << row.at("outflow_rate") / row.at("flow_rate")
          << ", K / (R^2 / 8) = " << std::setprecision(3)
          << row.at("permeability") / k_exact << std::endl;
}
