// The units in the statistics header (io::column_unit): a 3D scene's SI
// units, and a 2D scene's per metre of depth for its extensive quantities
// (forces, energies, flow rates, volumes, error norms), the intensive ones
// (pressures, velocities, permeabilities, times) unchanged.
#include <softsand/io/column_units.h>

#include "tests.h"

int
main()
{
  initlog();
  for (const std::string column :
       {"time", "grain_force_x", "kinetic_energy", "flow_rate",
        "open_pore_volume", "pressure_drop", "superficial_velocity",
        "permeability", "grain0_wz", "velocity_l2_error", "velocity_h1_error",
        "pressure_l2_error", "porosity_cells"})
    deallog << column << ": 3D " << softsand::io::column_unit(column, 3)
            << ", 2D " << softsand::io::column_unit(column, 2) << std::endl;
}
