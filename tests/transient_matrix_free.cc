// The transient matrix-free step (fluid solver/transient solver = matrix
// free) against the matrix-based one on the same coupled scene: a small
// radial Hele-Shaw cell (inlet reservoir at 4 kPa inside r = 0.6 mm, 0 Pa
// outside r = 2.2 mm, no-slip plates 1.2 mm apart on box cells of
// 0.25 x 0.25 x 0.24 mm) with eight free grains in a ring, rigid nodes, the
// rigid-node pressure smoothing and the traction faces of the reservoirs,
// two transient steps (BDF1, then BDF2 with the grains moved by the DEM).
// Both solve the same discrete equations: at a linear tolerance of 1e-10
// the flow rate and the fluid force and torque on every grain must agree
// to 1e-6, the grains' kinetic energy after the DEM to 1e-3. Checked also: the flow rate itself (a broken operator or right-hand
// side changes it) and the grains' forces are not zero. The same again
// with the paper's model in its limit (solid model = penalization limit,
// the default cell-average void fraction) on larger grains 2 um apart, whose shared
// cells give nodes blended from two grains (their reaction split by
// shares) and the squeeze relaxation of the pressure smoothing.

#include "tests.h"
#include "test_scenes.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace
{
  std::string
  scene(const std::string &solver,
        const std::string &directory,
        const bool         paper_model)
  {
    // Rigid nodes: eight grains of 0.3 mm on a ring of 1.2 mm; the limit:
    // 0.458 mm, neighbours 2.4 um apart.
    const std::string r = paper_model ? "4.58e-4" : "3e-4";
    std::string grains;
    const double ring[8][2] = {{1.2e-3, 0},          {8.485e-4, 8.485e-4},
                               {0, 1.2e-3},          {-8.485e-4, 8.485e-4},
                               {-1.2e-3, 0},         {-8.485e-4, -8.485e-4},
                               {0, -1.2e-3},         {8.485e-4, -8.485e-4}};
    for (const auto &c : ring)
      {
        std::ostringstream g;
        g << (grains.empty() ? "" : "; ") << c[0] << ", " << c[1]
          << ", 6e-4, " << r;
        grains += g.str();
      }
    return R"(
set dimension = 3
subsection simulation control
  set mode      = coupled
  set time step = 1e-4
  set end time  = 2e-4
end
subsection coupling
  set fluid model        = transient
  set max courant number = 100
end
subsection mesh
  set lower corner       = -2.5e-3, -2.5e-3, 0
  set upper corner       = 2.5e-3, 2.5e-3, 1.2e-3
  set coarse cells       = 20, 20, 5
  set cells per diameter = 0
  set allow unresolved grains = true
end
subsection grains
  set source = list
  set list   = )" +
           grains + R"(
end
subsection dem
  subsection material
    set density        = 2650
    set youngs modulus = 5e6
    set poisson ratio  = 0.15
    set restitution    = 0.7
    set friction       = 0.7
  end
  subsection walls
    set box  = z-, z+
    set list = cylinder 0 0 0 0 0 1 6e-4 outside
  end
end
subsection fluid
  set density            = 1000
  set viscosity          = 0.01
  set solid model        = )" +
           std::string(paper_model ? "penalization limit" : "rigid nodes") +
           R"(
  set free contact cells = false
end
subsection fluid solver
  set linear tolerance      = 1e-10
  set max linear iterations = 3000
  set transient solver      = )" +
           solver + R"(
end
subsection boundary conditions
  subsection x min
    set type = pressure
  end
  subsection x max
    set type = pressure
  end
  subsection y min
    set type = pressure
  end
  subsection y max
    set type = pressure
  end
  subsection inlet region
    set type     = cylinder
    set center   = 0, 0, 0
    set axis     = 0, 0, 1
    set radius   = 6e-4
    set pressure = 4000
  end
  subsection perimeter region
    set type     = cylinder
    set center   = 0, 0, 0
    set axis     = 0, 0, 1
    set radius   = 2.2e-3
    set pressure = 0
  end
end
subsection postprocessing
  subsection radial flow
    set radii = 1.6e-3, 2e-3
  end
end
subsection output
  set directory = )" +
           directory + R"(
  set write vtu = false
  set verbosity = quiet
end
)";
  }

  /// Per grain: fx fy fz tx ty tz of <directory>/grain_forces.txt.
  std::vector<std::array<double, 6>>
  grain_forces(const std::string &directory)
  {
    std::ifstream                      in(directory + "/grain_forces.txt");
    std::vector<std::array<double, 6>> forces;
    for (std::string line; std::getline(in, line);)
      {
        if (line.empty() || line[0] == '#')
          continue;
        std::istringstream words(line);
        double             skip;
        for (unsigned int i = 0; i < 5; ++i)
          words >> skip;
        std::array<double, 6> f;
        for (auto &v : f)
          words >> v;
        forces.push_back(f);
      }
    return forces;
  }
} // namespace


namespace
{
  /// Both paths on the scene of @p paper_model; each line of the log starts
  /// with @p label.
  void
  compare_paths(const bool paper_model, const std::string &label)
  {
    const std::string stem    = paper_model ? "limit" : "rigid";
    const std::string old_dir = stem + "_old", new_dir = stem + "_new";
    const auto old_path =
      run_scene<3>(scene("matrix based", old_dir, paper_model));
    const auto new_path =
      run_scene<3>(scene("matrix free", new_dir, paper_model));

    const double q = old_path.at("radial_flow_rate");
    deallog << label << ": steps " << old_path.at("step")
            << ", radial flow rate [mm^3/s] " << std::setprecision(4)
            << q * 1e9 << std::setprecision(6) << std::endl;
    const auto agree = [](const double a, const double b, const double scale) {
      return std::abs(a - b) <= 1e-6 * scale ? "yes" : "NO";
    };
    deallog << label << ": flow rate agrees to 1e-6: "
            << agree(q, new_path.at("radial_flow_rate"), std::abs(q))
            << std::endl;
    // The held force's secant over the last two solves amplifies the
    // solvers' 1e-7 differences in the grains' motion: 1e-3 there.
    const double energy =
      read_statistics(old_dir + "/statistics.txt").at("kinetic_energy").back();
    const double new_energy =
      read_statistics(new_dir + "/statistics.txt").at("kinetic_energy").back();
    deallog << label << ": grains moved (kinetic energy > 0): "
            << (energy > 0 ? "yes" : "NO") << ", agrees to 1e-3: "
            << (std::abs(energy - new_energy) <= 1e-3 * energy ? "yes" : "NO")
            << std::endl;

    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        const auto f_old = grain_forces(old_dir);
        const auto f_new = grain_forces(new_dir);
        double     largest_force = 0, largest_torque = 0,
               force_difference = 0, torque_difference = 0;
        for (unsigned int g = 0; g < f_old.size(); ++g)
          for (unsigned int c = 0; c < 3; ++c)
            {
              largest_force = std::max(largest_force, std::abs(f_old[g][c]));
              largest_torque =
                std::max(largest_torque, std::abs(f_old[g][c + 3]));
              force_difference =
                std::max(force_difference,
                         std::abs(f_old[g][c] - f_new[g][c]));
              torque_difference =
                std::max(torque_difference,
                         std::abs(f_old[g][c + 3] - f_new[g][c + 3]));
            }
        deallog << label << ": grains " << f_old.size() << " (both paths "
                << f_new.size() << "), largest fluid force [mN] "
                << std::setprecision(3) << largest_force * 1e3
                << std::setprecision(6) << std::endl;
        deallog << label << ": forces agree to 1e-6 of the largest: "
                << (force_difference <= 1e-6 * largest_force ? "yes" : "NO")
                << ", torques (on the scale force x radius; the ring is "
                   "symmetric): "
                << (torque_difference <=
                        1e-6 * std::max(largest_torque, largest_force * 3e-4) ?
                      "yes" :
                      "NO")
                << std::endl;
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  compare_paths(false, "rigid nodes");
  compare_paths(true, "penalization limit");
}
