// The inlet and perimeter pressure regions on a grain-free radial
// Hele-Shaw cell: two no-slip plates a gap h = 0.25 mm apart, the fluid
// inside r_i = 1 mm a reservoir at p_i = 1 kPa, outside r_o = 3 mm one at
// p_o = 0 (boundary conditions/inlet region, perimeter region), steady
// Stokes, mu = 10 cP. Between the plates the exact Stokes solution is the
// radial Poiseuille flow u_r = (dp/dr) z (z - h) / (2 mu) with
//   p(r) = p_i - (p_i - p_o) ln(r / r_i) / ln(r_o / r_i),
//   Q    = 2 pi h^3 (p_i - p_o) / (12 mu ln(r_o / r_i))
// (it satisfies the Stokes equations exactly: the vector Laplacian of
// f(z)/r e_r is f''(z)/r e_r). The regions impose the traction -p n on
// their staircase surfaces (cells whose centre lies inside r_i / outside
// r_o), which differs from p = p_i by the viscous normal stress, of
// relative order h^2 / (12 r_i^2 ln(r_o/r_i)) = 0.5 % here. One Q2 cell
// spans the gap (the parabola is exact); in-plane cells are 0.1 mm.
// Checked: ring pressures and the flow rate against the formulas.

#include "tests.h"
#include "test_scenes.h"

#include <cmath>

namespace
{
  const char *scene = R"(
set dimension = 3
subsection simulation control
  set mode = steady stokes
end
subsection mesh
  set lower corner       = -3.2e-3, -3.2e-3, 0
  set upper corner       = 3.2e-3, 3.2e-3, 0.25e-3
  set coarse cells       = 64, 64, 1
  set cells per diameter = 0
end
subsection fluid
  set density   = 1000
  set viscosity = 0.01
end
subsection fluid solver
  set linear tolerance = 1e-10
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
    set radius   = 1e-3
    set pressure = 1000
  end
  subsection perimeter region
    set type     = cylinder
    set center   = 0, 0, 0
    set axis     = 0, 0, 1
    set radius   = 3e-3
    set pressure = 0
  end
end
subsection postprocessing
  subsection radial flow
    set radii           = 1.25e-3, 1.5e-3, 2e-3, 2.5e-3, 2.75e-3
    set ring half width = 0.05e-3
  end
end
subsection output
  set directory   = results
  set write vtu   = false
  set verbosity   = quiet
end
)";
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const auto   r   = run_scene<3>(scene);
  const double p_i = 1000, p_o = 0, r_i = 1e-3, r_o = 3e-3, h = 0.25e-3,
               mu  = 0.01;
  const double radii[] = {1.25e-3, 1.5e-3, 2e-3, 2.5e-3, 2.75e-3};
  double       worst   = 0;
  for (unsigned int k = 0; k < 5; ++k)
    {
      const double exact =
        p_i - (p_i - p_o) * std::log(radii[k] / r_i) / std::log(r_o / r_i);
      const double p     = r.at("ring_pressure_" + std::to_string(k));
      const double error = (p - exact) / (p_i - p_o);
      worst              = std::max(worst, std::abs(error));
      deallog << "r = " << std::setprecision(2) << radii[k] * 1e3
              << " mm: p / p_i " << std::setprecision(3) << p / p_i
              << ", exact " << exact / p_i << std::setprecision(6)
              << std::endl;
    }
  deallog << "ring pressures within 1% of (p_i - p_o) of the log profile: "
          << (worst < 1e-2 ? "yes" : "NO") << std::endl;
  const double Q_exact =
    2 * M_PI * h * h * h * (p_i - p_o) / (12 * mu * std::log(r_o / r_i));
  const double Q = r.at("radial_flow_rate");
  deallog << "flow rate / exact " << std::setprecision(3) << Q / Q_exact
          << std::setprecision(6) << ", within 2%: "
          << (std::abs(Q / Q_exact - 1) < 2e-2 ? "yes" : "NO") << std::endl;
  // The permeability of an empty gap is h^2 / 12.
  const double K = r.at("radial_permeability");
  deallog << "radial permeability / (h^2/12) " << std::setprecision(3)
          << K / (h * h / 12) << std::setprecision(6) << std::endl;
}
