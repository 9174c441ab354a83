#ifndef softsand_coupling_held_force_model_h
#define softsand_coupling_held_force_model_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/tensor.h>
#include <deal.II/particles/particle.h>

#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_locator.h>
#include <softsand/dem/grain.h>

#include <array>
#include <iosfwd>
#include <vector>

namespace softsand
{
  namespace coupling
  {
    using namespace dealii;

    /// The fluid's force and torque on each grain, held over the DEM
    /// sub-steps of a coupling step, with their linear response to the
    /// grain's velocity (N s/m) and angular velocity (N m s), per grain id.
    struct HeldForces
    {
      std::vector<Tensor<1, 3>> force, torque;
      std::vector<double>       resistance, rotational_resistance;
    };

    /**
     * The penalty coupling number N = Theta (rho_f / rho_s) h^3 / V of the
     * penalization: a cell of edge h shared by two grains (or by a grain and
     * a wall) cannot follow both rigid velocities, and the penalty there
     * holds the two together with about rho Theta h^3 (u_A - u_B) / dt.
     * Over one coupling step that changes a grain of volume V by N times the
     * velocity difference, whatever dt; a fluid force held explicitly over
     * the step then grows from step to step where N is large
     * (doc/hele_shaw.md, "The injection with the paper's model").
     */
    double
    penalty_coupling_number(const double theta,
                            const double fluid_density,
                            const double grain_density,
                            const double cell_edge,
                            const double grain_volume);

    /// Above this penalty coupling number the coupled step was measured
    /// unstable: the small Hele-Shaw scene at 4 cells per mean diameter ran
    /// at N = 36 (Theta = 1e3) and blew up at N = 362 (Theta = 1e4).
    constexpr double max_stable_penalty_coupling = 100;

    /**
     * The fluid force seen by the DEM between two fluid solves, linearized
     * in the grain's velocity, F(v) = F_0 - k (v - v_0) (doc/architecture.md,
     * "Held fluid force"). The resistance k is Stokes' 3 pi mu d (rotation:
     * pi mu d^3); the transient fluid adds the added mass and a viscous
     * shell set in motion within the step; where the last two solves
     * measured a larger resistance (crowded grains, walls, thin fluid
     * layers of contacts), their secant. Owns the history of the last solve
     * per grain id, which a checkpoint saves.
     */
    class HeldForceModel
    {
    public:
      struct Settings
      {
        double viscosity     = 0; ///< Pa s
        double fluid_density = 0; ///< kg/m^3
        /// Transient fluid model (else quasi-steady Stokes).
        bool transient = false;
        /// Rigid-node solids: the fluid nodes inside a grain follow it.
        bool   rigid_nodes            = false;
        double added_mass_coefficient = 0.5;
        /// Buoyancy added to the held force (the fluid is solved without
        /// its hydrostatic pressure).
        bool         buoyancy = false;
        Tensor<1, 3> gravity;
        /// The box, and which of its faces (2 d, 2 d + 1) impose a
        /// velocity: only those hold a fluid layer against a grain.
        BoundingBox<3>      box;
        std::array<bool, 6> face_imposes_velocity{};
      };

      explicit HeldForceModel(const Settings &settings);

      /// The held forces after a fluid solve of step @p dt, from the fluid
      /// forces of the grains (in the order of @p grains, whose ids are
      /// @p ids); updates the history.
      HeldForces
      compute(const std::vector<dem::Grain<3>>          &grains,
              const std::vector<types::particle_index> &ids,
              const GrainForces<3>                      &fluid_forces,
              const GrainLocator<3>                     &locator,
              const double                              finest_cell,
              const double                              dt);

      void
      save(std::ostream &out) const;
      /// Reads what save() wrote; stops with a message naming @p source if
      /// it is truncated.
      void
      load(std::istream &in, const std::string &source);

    private:
      /// Each grain's gap to the nearest wall face with an imposed velocity
      /// or other grain, searched up to max(2 r, @p finest_cell).
      std::vector<double>
      clearances(const std::vector<dem::Grain<3>> &grains,
                 const GrainLocator<3>            &locator,
                 const double                      finest_cell) const;

      const Settings settings;

      /// Per grain id at the last fluid solve.
      struct History
      {
        std::vector<Tensor<1, 3>> velocity, force, angular_velocity, torque;
        std::vector<double>       resistance, rotational_resistance;
        void
        resize(const std::size_t n);
      } history;
    };
  } // namespace coupling
} // namespace softsand

#endif
