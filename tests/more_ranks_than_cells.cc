// Every rank reaches every collective, also ranks that own no cell: a fluid
// scene on a 1-cell mesh and a granular scene on a 1-cell contact mesh run
// to their end on 2 ranks (they hung in an MPI_Allreduce before). A fluid
// mesh too coarse for its grains stops with a message naming
// mesh/cells per diameter unless mesh/allow unresolved grains is set.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>

#include <cmath>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const std::string one_cell = scene_text("drag_sphere") +
                               "subsection mesh\n set coarse cells = 1, 1, 1\n"
                               " set cells per diameter = 0\nend\n";

  // Too coarse: the 1 mm sphere in one 10 mm cell.
  try
    {
      run_scene<3>(one_cell);
      deallog << "unresolved sphere: accepted (wrong)" << std::endl;
    }
  catch (const std::exception &e)
    {
      deallog << "unresolved sphere: " << softsand::base::error_message(e)
              << std::endl;
    }

  // Allowed: one cell on two ranks runs to its end.
  {
    const auto r = run_scene<3>(one_cell + "subsection mesh\n"
                                           " set allow unresolved grains = "
                                           "true\nend\n");
    deallog << "1 cell, " << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
            << " ranks: cells " << int(r.at("cells")) << ", DoFs "
            << int(r.at("dofs"))
            << ", pressure drop finite: "
            << (std::isfinite(r.at("pressure_drop")) ? "yes" : "no")
            << std::endl;
  }

  // A transient run on the same mesh.
  {
    const auto r = run_scene<3>(
      one_cell + "subsection mesh\n set allow unresolved grains = true\nend\n"
                 "subsection simulation control\n set mode = transient\n"
                 " set end time = 3e-3\nend\n");
    deallog << "1 cell, transient: steps " << int(r.at("step")) << ", time "
            << r.at("time") << std::endl;
  }

  // Grains alone: two grains falling in a box narrower than one contact
  // range, so the contact mesh has a single cell.
  {
    const auto r = run_granular_scene(
      "subsection simulation control\n set mode = granular\n"
      " set end time = 2e-3\nend\n"
      "subsection mesh\n set lower corner = 0, 0, 0\n"
      " set upper corner = 3e-4, 3e-4, 3e-4\nend\n"
      "subsection grains\n set source = list\n"
      " set list = 1.5e-4, 1.5e-4, 0.6e-4, 5e-5; 1.5e-4, 1.5e-4, 1.9e-4, "
      "5e-5\nend\n"
      "subsection output\n set directory = results\n set write vtu = false\n"
      " set verbosity = quiet\nend\n");
    deallog << "granular, 1 cell: grains " << int(r.at("grains"))
            << ", lost " << int(r.at("lost_grains")) << ", end time reached "
            << r.at("time") << std::endl;
  }
}
