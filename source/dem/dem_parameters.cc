#include <softsand/base/parameter_tools.h>
#include <softsand/dem/dem_parameters.h>

namespace softsand
{
  namespace dem
  {
    void
    DEMParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("dem");
      Material::declare_parameters(prm);
      WallParameters::declare_parameters(prm);
      prm.declare_entry("rolling model", "none",
                        Patterns::Selection("none|constant torque|elastic plastic"),
                        "Rolling resistance: constant directional torque "
                        "mu_r R* |F_n|, or an elastic-plastic spring limited "
                        "to that torque (LIGGGHTS cdt / epsd2).");
      prm.declare_entry("time step", "0", Patterns::Double(0),
                        "DEM time step (s); 0: 'automatic rayleigh fraction' "
                        "times the Rayleigh time of the smallest grain.");
      prm.declare_entry("automatic rayleigh fraction", "0.2",
                        Patterns::Double(0),
                        "dt / Rayleigh time when the time step is 0.");
      prm.declare_entry("max rayleigh fraction", "0.35", Patterns::Double(0),
                        "A time step above this fraction of the Rayleigh time "
                        "stops the run: contacts would be unstable.");
      prm.declare_entry("contact stability number", "0.8",
                        Patterns::Double(0, 2),
                        "With time step = 0 the step also follows the "
                        "contacts: omega dt and c dt of the stiffest grain "
                        "(sum of its contact stiffnesses and dampings, "
                        "tangential ones on 2/7 of the mass) stay at most "
                        "this. Hertz contacts stiffen with the overlap, so "
                        "cohesive or compressed packs need smaller steps "
                        "than the Rayleigh time suggests.");
      prm.declare_entry("gravity", "0, 0, 0", Patterns::Anything(),
                        "Gravity vector (m/s^2).");
      prm.declare_entry("skin", "0.25", Patterns::Double(0),
                        "Verlet skin as a fraction of the largest radius; "
                        "neighbour lists are rebuilt when a grain moved half "
                        "of it.");
      prm.declare_entry("settled kinetic energy", "0", Patterns::Double(0),
                        "Stop once the kinetic energy per grain (J) stays "
                        "below this for 'settled checks' statistics rows; "
                        "0: run to the end time.");
      prm.declare_entry("settled checks", "5", Patterns::Integer(1),
                        "Consecutive statistics rows below the threshold.");
      prm.declare_entry("statistics interval", "100", Patterns::Integer(1),
                        "DEM steps between statistics rows.");
      prm.declare_entry("output interval", "0", Patterns::Integer(0),
                        "DEM steps between grain VTU outputs (0: first and "
                        "last only).");
      prm.declare_entry("probe box", "", Patterns::Anything(),
                        "Probe 'x0, y0, z0, x1, y1, z1' of the packing "
                        "fraction (grain volume with the centre inside over "
                        "the box volume) and the contact stress (Love-Weber "
                        "sum over those grains, over the box volume); empty: "
                        "the mesh box.");
      prm.declare_entry("save pack", "", Patterns::Anything(),
                        "Write the final grains to this file (x y z radius "
                        "vx vy vz wx wy wz), relative to the output "
                        "directory; empty: do not.");
      prm.declare_entry("save initial pack", "", Patterns::Anything(),
                        "Write the inserted grains before the first step, "
                        "same format (e.g. to start another code from the "
                        "same pack); empty: do not.");
      prm.leave_subsection();
    }


    void
    DEMParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("dem");
      material.parse_parameters(prm);
      walls.parse_parameters(prm);
      const std::string r = prm.get("rolling model");
      rolling_model = (r == "none") ? RollingModel::none :
                      (r == "constant torque") ? RollingModel::constant_torque :
                                                 RollingModel::elastic_plastic;
      time_step                   = prm.get_double("time step");
      automatic_rayleigh_fraction = prm.get_double("automatic rayleigh fraction");
      max_rayleigh_fraction       = prm.get_double("max rayleigh fraction");
      if (!(automatic_rayleigh_fraction > 0) ||
          automatic_rayleigh_fraction > max_rayleigh_fraction)
        base::throw_invalid_parameter(
          "dem/automatic rayleigh fraction",
          prm.get("automatic rayleigh fraction"),
          "it must lie in (0, max rayleigh fraction = " +
            prm.get("max rayleigh fraction") + "]");
      stability_number = prm.get_double("contact stability number");
      if (!(stability_number > 0))
        base::throw_invalid_parameter("dem/contact stability number",
                                      prm.get("contact stability number"),
                                      "it must lie in (0, 2]");
      gravity       = base::get_tensor<3>(prm, "gravity");
      skin_fraction = prm.get_double("skin");
      if (!(skin_fraction > 0))
        base::throw_invalid_parameter("dem/skin", prm.get("skin"),
                                      "it must be > 0");
      settled_kinetic_energy = prm.get_double("settled kinetic energy");
      settled_checks         = prm.get_integer("settled checks");
      statistics_interval    = prm.get_integer("statistics interval");
      output_interval        = prm.get_integer("output interval");
      if (!prm.get("probe box").empty())
        probe_box = base::get_double_list(prm, "probe box", 6);
      save_pack         = prm.get("save pack");
      save_initial_pack = prm.get("save initial pack");
      prm.leave_subsection();
    }
  } // namespace dem
} // namespace softsand
