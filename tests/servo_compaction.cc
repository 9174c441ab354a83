// Servo compaction (parameters/pour_and_compact.prm: a piston drives the
// poured Fig. 3 pack to 10 kPa): the run stops only once the pack has
// settled with the piston within 2% of the target for 20 statistics rows in
// a row (10,000 steps), so "settled" means the pressure was reached and
// held; the largest deviation over those rows is printed.

#include <deal.II/base/mpi.h>

#include <sstream>

#include "test_scenes.h"
#include "tests.h"

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  std::stringstream text;
  text << scene_text("pour_and_compact")
       << "subsection dem\n set save pack =\n set settled checks = 20\nend\n";
  const auto r = run_granular_scene(text.str());
  deallog << "settled with the piston within 2% for 10,000 steps: "
          << (r.at("settled") > 0 ? "yes" : "no") << std::endl;
  deallog << "largest piston pressure error over those steps below 0.5%: "
          << (r.at("settled_servo_max_error") < 5e-3 ? "yes" : "no")
          << std::endl;
  deallog << "final piston pressure within 0.5% of 10 kPa: "
          << (std::abs(r.at("wall_0_pressure") / 1e4 - 1) < 5e-3 ? "yes" : "no")
          << std::endl;
}
