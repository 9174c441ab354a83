#include <softsand/base/parameter_tools.h>
#include <softsand/core/simulation_control.h>

namespace softsand
{
  namespace core
  {
    void
    SimulationControl::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("simulation control");
      prm.declare_entry(
        "mode",
        "steady stokes",
        Patterns::Selection(
          "steady stokes|steady navier stokes|transient|granular|coupled"),
        "steady stokes: one Stokes-Brinkman solve; steady navier stokes: "
        "Newton or Picard iterations to the steady state of the penalized "
        "scheme; transient: BDF time marching of the paper's Eq. (6); "
        "granular: grains alone under contacts, walls and gravity (the "
        "DEM; no fluid system is built); coupled: grains moved by the DEM "
        "in the fluid (CFD-DEM, subsection coupling).");
      prm.declare_entry("time step",
                        "1e-4",
                        Patterns::Double(0),
                        "Fluid time step (s). In the steady modes it is the "
                        "penalty time scale in rho (1 + Theta (1 - vf)) "
                        "(1 - vf) / dt. Coupled runs: the fluid step "
                        "(transient fluid) or the largest coupling step "
                        "(quasi-steady fluid).");
      prm.declare_entry("end time",
                        "1e-3",
                        Patterns::Double(0),
                        "End time of a transient, granular or coupled run (s).");
      prm.declare_entry("checkpoint interval",
                        "0",
                        Patterns::Integer(0),
                        "Transient, granular and coupled runs: write a "
                        "checkpoint (mesh and fluid fields; grains, contact "
                        "histories and walls) every this many time steps "
                        "(coupling steps; DEM steps in a granular run) into "
                        "the output directory, replacing the previous one "
                        "once it is complete (0: never).");
      prm.declare_entry("restart",
                        "false",
                        Patterns::Bool(),
                        "Transient, granular and coupled runs: continue "
                        "from the checkpoint in the output directory "
                        "instead of starting anew; statistics rows and "
                        "output series continue (rows the stopped run wrote "
                        "after its checkpoint are replaced). The scene's "
                        "other parameters must be those of the first run.");
      prm.declare_entry("max time steps",
                        "1000000",
                        Patterns::Integer(1),
                        "Upper bound on the number of time steps.");
      prm.declare_entry("time scheme",
                        "BDF2",
                        Patterns::Selection("BDF1|BDF2"),
                        "Time discretization of the transient mode.");
      prm.declare_entry(
        "steady state tolerance",
        "0",
        Patterns::Double(0),
        "A transient run stops once ||u^{n+1} - u^n|| / ||u^{n+1}|| falls "
        "below this value (dimensionless; 0 = run to the end time).");
      prm.leave_subsection();
    }


    void
    SimulationControl::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("simulation control");
      const std::string m = prm.get("mode");
      mode = (m == "steady stokes") ?
               Mode::steady_stokes :
               (m == "steady navier stokes" ? Mode::steady_navier_stokes :
                (m == "granular" ? Mode::granular :
                                   (m == "coupled" ? Mode::coupled :
                                                     Mode::transient)));
      time_step = prm.get_double("time step");
      if (!(time_step > 0))
        base::throw_invalid_parameter("simulation control/time step",
                                prm.get("time step"),
                                "the time step must be > 0 s");
      end_time               = prm.get_double("end time");
      max_time_steps         = prm.get_integer("max time steps");
      bdf_order              = (prm.get("time scheme") == "BDF1") ? 1 : 2;
      steady_state_tolerance = prm.get_double("steady state tolerance");
      checkpoint_interval    = prm.get_integer("checkpoint interval");
      restart                = prm.get_bool("restart");
      if ((mode == Mode::transient || mode == Mode::granular ||
           mode == Mode::coupled) &&
          !(end_time > 0))
        base::throw_invalid_parameter("simulation control/end time",
                                prm.get("end time"),
                                "a transient, granular or coupled run needs an end time > 0 s");
      // Steady runs have no time loop to checkpoint: a setting the run
      // would ignore stops it instead.
      if (is_steady() && restart)
        base::throw_invalid_parameter(
          "simulation control/restart",
          "true",
          "only runs with a time loop (mode = transient, granular or "
          "coupled) restart from a checkpoint; this " + prm.get("mode") +
            " run has none (set restart = false)");
      if (is_steady() && checkpoint_interval > 0)
        base::throw_invalid_parameter(
          "simulation control/checkpoint interval",
          prm.get("checkpoint interval"),
          "only runs with a time loop (mode = transient, granular or "
          "coupled) write checkpoints; set it to 0 for this " +
            prm.get("mode") + " run");
      prm.leave_subsection();
    }
  } // namespace core
} // namespace softsand
