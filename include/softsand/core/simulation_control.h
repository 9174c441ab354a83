#ifndef softsand_core_simulation_control_h
#define softsand_core_simulation_control_h

#include <deal.II/base/parameter_handler.h>

namespace softsand
{
  namespace core
  {
    using namespace dealii;

    /**
     * Which problem is solved and how time advances: a steady solve (one
     * linear or nonlinear solve gives the answer: permeability, fixed-sphere
     * drag) or time marching of the penalized scheme (the paper's Eq. 6).
     */
    struct SimulationControl
    {
      enum class Mode
      {
        steady_stokes,
        steady_navier_stokes,
        transient,
        granular,
        coupled
      };

      Mode         mode = Mode::steady_stokes;
      /// Fluid time step; in steady modes the penalty time scale of the
      /// Brinkman term rho (1 + Theta (1 - vf)) (1 - vf) / dt.
      double       time_step = 1e-4;
      double       end_time  = 1e-3;
      unsigned int max_time_steps = 1000000;
      /// 1 = BDF1 (backward Euler), 2 = BDF2.
      unsigned int bdf_order = 2;
      /// Transient runs stop when the relative velocity change per step
      /// falls below this value (0: never).
      double       steady_state_tolerance = 0;
      /// Coupled runs: checkpoint every this many steps (0: never), and
      /// whether to continue from the checkpoint.
      unsigned int checkpoint_interval = 0;
      bool         restart             = false;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      bool
      is_steady() const
      {
        return mode == Mode::steady_stokes ||
               mode == Mode::steady_navier_stokes;
      }

      /// Whether a time loop at @p time after @p step steps is done: the
      /// end time reached (within 1e-12 of it) or the step limit.
      bool
      reached_end(const double time, const unsigned long step) const
      {
        return time >= end_time * (1 - 1e-12) || step >= max_time_steps;
      }
    };
  } // namespace core
} // namespace softsand

#endif
