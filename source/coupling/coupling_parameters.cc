#include <softsand/base/parameter_tools.h>
#include <softsand/coupling/coupling_parameters.h>

namespace softsand
{
  namespace coupling
  {
    void
    CouplingParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      prm.declare_entry(
        "fluid model",
        "transient",
        Patterns::Selection("transient|quasi-steady"),
        "transient: the paper's BDF marching of the penalized Navier-Stokes "
        "equations, one fluid step (simulation control/time step) per "
        "coupling step; quasi-steady: one steady Stokes-Brinkman solve per "
        "coupling step with the grains' current velocities (creeping flow, "
        "pore Reynolds number << 1), the step set by grain displacement.");
      prm.declare_entry(
        "readapt fraction",
        "0.5",
        Patterns::Double(0),
        "Re-adapt the fluid mesh once a grain has moved this fraction of the "
        "finest cell edge since the last adaptation (dimensionless, > 0); "
        "cells within that distance of a grain surface are kept fine.");
      prm.declare_entry(
        "max displacement fraction",
        "0.25",
        Patterns::Double(0),
        "Quasi-steady fluid: the coupling step lets the fastest grain move at "
        "most this fraction of the finest cell edge (dimensionless, > 0), "
        "and at most simulation control/time step.");
      prm.declare_entry(
        "max courant number",
        "0",
        Patterns::Double(0),
        "Transient fluid: halve the coupling step (simulation control/time "
        "step, halved up to 10 times) while the largest cell Courant number "
        "|u| dt / h of the last fluid solution exceeds this, and double it "
        "back where it stays within this, never in two steps running "
        "(variable-step BDF2; dimensionless; 0: fixed steps). The "
        "velocity V-cycle of the Oseen step fails at Courant numbers of a "
        "few (doc/notes/solver_study.md). With fluid/solid model = penalization "
        "the step is also the penalty's time scale: leave it 0 there.");
      prm.declare_entry(
        "max velocity change",
        "0",
        Patterns::Double(0),
        "Transient fluid: the step's accuracy limit. Halve the coupling step "
        "(as for the Courant number, and with the same doubling rule) while "
        "the relative change of the velocity field per step, ||u^n+1 - "
        "u^n|| / ||u^n+1||, predicted from the last step's (it is "
        "proportional to the step), exceeds this (dimensionless; 0: off). "
        "The pore flow of an injection is not steady, and a step that "
        "changes it by a fifth gives a flow rate 3 % low, one that changes "
        "it by half 14 % (doc/notes/solver_study.md); the shipped injection "
        "scenes set 0.1.");
      prm.declare_entry("dem substeps",
                        "0",
                        Patterns::Integer(0),
                        "DEM steps per coupling step (0: as many as the "
                        "DEM's stable step needs; see dem/time step).");
      prm.declare_entry(
        "added mass coefficient",
        "0.5",
        Patterns::Double(0),
        "The fluid force on a grain is computed once per coupling step and "
        "held over the DEM sub-steps; meanwhile it follows the grain's "
        "velocity v as F - K (v - v_n): K = 3 pi mu d (Stokes drag) plus, "
        "with the transient fluid, rho_f / dt (C V + pi d^2 l), the fluid a "
        "change of velocity must set in motion within the coupling step dt: "
        "the added mass C V and a shell l = max(finest cell, sqrt(pi nu dt)) "
        "thick. This C is dimensionless (0.5: a sphere's potential-flow "
        "added mass). The response keeps the explicit coupling stable; it "
        "does not change steady motion.");
      prm.declare_entry(
        "buoyancy",
        "true",
        Patterns::Bool(),
        "Add the hydrostatic force -rho_f V g (dem/gravity) on each grain. "
        "The fluid then solves for the pressure without its hydrostatic "
        "part (leave fluid/body force at zero).");
      prm.declare_entry(
        "force model",
        "penalization reaction",
        Patterns::Selection("penalization reaction|paper eq7"),
        "Fluid force on a grain: the penalization reaction (the exact "
        "discrete force; it balances the boundary tractions) or the paper's "
        "Eq. (7), mu lap u - grad p over the grain's cells (misses the "
        "stress jumps across faces).");
      prm.declare_entry(
        "cut cell weight",
        "3",
        Patterns::Double(0),
        "Load balancing of the fluid mesh: a cell cut by a grain surface "
        "costs this many plain cells (assembly evaluates the grains at its "
        "quadrature points).");
      prm.leave_subsection();
    }


    void
    CouplingParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      fluid_model = (prm.get("fluid model") == "quasi-steady") ?
                      FluidModel::quasi_steady :
                      FluidModel::transient;
      readapt_fraction = prm.get_double("readapt fraction");
      if (!(readapt_fraction > 0) || readapt_fraction > 4)
        base::throw_invalid_parameter("coupling/readapt fraction",
                                      prm.get("readapt fraction"),
                                      "a fraction of the finest cell in (0, 4]");
      max_displacement_fraction = prm.get_double("max displacement fraction");
      if (!(max_displacement_fraction > 0) || max_displacement_fraction > 4)
        base::throw_invalid_parameter("coupling/max displacement fraction",
                                      prm.get("max displacement fraction"),
                                      "a fraction of the finest cell in (0, 4]");
      max_courant_number = prm.get_double("max courant number");
      max_velocity_change = prm.get_double("max velocity change");
      if (max_velocity_change > 1)
        base::throw_invalid_parameter(
          "coupling/max velocity change",
          prm.get("max velocity change"),
          "a relative change per step in [0, 1] (0: off): above 1 the "
          "step could replace the flow entirely and still be accepted");
      dem_substeps    = prm.get_integer("dem substeps");
      added_mass_coefficient = prm.get_double("added mass coefficient");
      buoyancy        = prm.get_bool("buoyancy");
      paper_force     = (prm.get("force model") == "paper eq7");
      cut_cell_weight = prm.get_double("cut cell weight");
      prm.leave_subsection();
    }
  } // namespace coupling
} // namespace softsand
