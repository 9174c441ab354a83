// Momentum balance of a steady pack: flow through four fixed grains in a
// channel (flow-rate inlet, pressure outlet, no-slip walls). The fluid force
// on the grains (the penalization reaction) and the fluid force on the box
// faces (the reaction of their constrained rows plus the outlet pressure)
// must cancel: the discrete balance closes to the solver tolerance (1e-6
// relative asked; the target is 1 %). The surface integral of the
// traction mu du/dn - p n over the faces, an independent but coarser
// estimate (gradients of the discrete solution on the faces), agrees within
// 10 % at this resolution (4 % and 8 % measured).
// Both solid models are checked.

#include <deal.II/base/mpi.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  for (const std::string model : {"penalization", "rigid nodes"})
    {
      const auto r = run_scene<3>(
        "subsection mesh\n set lower corner = 0, 0, 0\n"
        " set upper corner = 2e-3, 1e-3, 1e-3\n set cells per diameter = 4\n"
        "end\n"
        "subsection grains\n set source = list\n"
        " set list = 5e-4, 3e-4, 3e-4, 2e-4; 9e-4, 7e-4, 5e-4, 2.5e-4;"
        " 1.5e-3, 4e-4, 6e-4, 2e-4; 1.5e-3, 7.5e-4, 2.5e-4, 1.8e-4\n"
        "end\n"
        "subsection fluid\n set density = 1000\n set viscosity = 1e-3\n"
        " set theta = 1e6\n set solid model = " +
        model +
        "\nend\n"
        "subsection boundary conditions\n"
        " subsection x min\n  set type = flow rate\n  set flow rate = 1e-9\n"
        " end\n"
        " subsection x max\n  set type = pressure\n end\n"
        "end\n"
        "subsection postprocessing\n set flow axis = x\nend\n"
        "subsection output\n set directory = results\n set write vtu = false\n"
        " set verbosity = quiet\nend\n");
      const double grains   = r.at("grain_force_x");
      const double discrete = std::abs(grains + r.at("boundary_reaction_x")) /
                              std::abs(grains);
      // The traction integral is the force of the boundary on the fluid.
      const double surface =
        std::abs(grains - r.at("boundary_force_x")) / std::abs(grains);
      deallog << model << ": grains pushed downstream: "
              << (grains > 0 ? "yes" : "no")
              << ", discrete balance within 1e-6: "
              << (discrete < 1e-6 ? "yes" : "no")
              << ", surface traction within 10 %: "
              << (surface < 0.1 ? "yes" : "no") << std::endl;
    }
}
