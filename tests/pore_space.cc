// The open pore space and its sealed pockets (postprocess::PoreConnectivity)
// in a 2D channel 2 x 1 mm of 0.1 mm cells, driven by 1 Pa from x min to
// x max between no-slip walls, rigid nodes. Two structures of touching
// disks (r = 0.1 mm, centres on the 0.2 mm lattice of cell corners):
//  - a ring of 8 disks around (0.5, 0.5) mm: the 2 x 2 cells at its centre
//    are open (uncovered) and every cell around them is more than half
//    covered, so they are a sealed pocket of exactly 4e-8 m^2;
//  - a wall of 5 disks across the channel at x = 1.5 mm: no open path from
//    the inlet face to the outlet face. Without its middle disk the path
//    opens through a 0.2 mm gap.
// Checked: open_path, the sealed area (4e-8 m^2 in both), the flow rate
// (through the wall only the leak of the rigid-node staircase at the
// contact points, 1/36 of the flow through the gap) and the warnings; on 1
// and on 2 ranks (the components are joined across ranks).

#include <softsand/base/warnings.h>

#include "test_scenes.h"
#include "tests.h"

#include <iomanip>

namespace
{
  std::string
  scene(const std::string &grains)
  {
    return R"(
set dimension = 2
subsection simulation control
  set mode = steady stokes
end
subsection mesh
  set lower corner       = 0, 0
  set upper corner       = 2e-3, 1e-3
  set coarse cells       = 20, 10
  set cells per diameter = 0
end
subsection fluid
  set viscosity   = 1e-3
  set solid model = rigid nodes
end
subsection boundary conditions
  subsection x min
    set type     = pressure
    set pressure = 1
  end
  subsection x max
    set type = pressure
  end
end
subsection grains
  set source = list
  set list   = )" +
           grains + R"(
end
subsection output
  set directory = results
  set write vtu = false
  set verbosity = quiet
end
)";
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  std::string ring;
  for (const double x : {0.3e-3, 0.5e-3, 0.7e-3})
    for (const double y : {0.3e-3, 0.5e-3, 0.7e-3})
      if (x != 0.5e-3 || y != 0.5e-3)
        ring += std::to_string(x) + ", " + std::to_string(y) + ", 1e-4; ";
  std::string wall, wall_with_gap;
  for (const double y : {0.1e-3, 0.3e-3, 0.5e-3, 0.7e-3, 0.9e-3})
    {
      const std::string disk = "1.5e-3, " + std::to_string(y) + ", 1e-4; ";
      wall += disk;
      if (y != 0.5e-3)
        wall_with_gap += disk;
    }

  for (const auto &[name, grains] :
       {std::make_pair("ring and closed wall", ring + wall),
        std::make_pair("ring and wall with a gap", ring + wall_with_gap)})
    {
      std::string list = grains;
      list.resize(list.size() - 2); // the last "; "
      const auto r = run_scene<2>(scene(list));
      deallog << std::scientific << std::setprecision(4) << name
              << ": open_path " << r.at("open_path")
              << ", sealed area "
              << r.at("sealed_pore_fraction") * r.at("open_pore_volume")
              << " m^2, flow rate " << r.at("flow_rate") << " m^2/s"
              << std::endl;
    }
  deallog << "warned: pockets "
          << (warned("lies in pockets") ? "yes" : "no") << ", closed path "
          << (warned("no open path joins the inlet") ? "yes" : "no")
          << std::endl;
}
