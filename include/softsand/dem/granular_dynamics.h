#ifndef softsand_dem_granular_dynamics_h
#define softsand_dem_granular_dynamics_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <softsand/dem/contact_law.h>
#include <softsand/dem/dem_parameters.h>
#include <softsand/dem/grain.h>
#include <softsand/dem/walls.h>

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /// Indices of the grain properties carried by the ParticleHandler.
    namespace property
    {
      constexpr unsigned int radius = 0, density = 1, velocity = 2,
                             angular_velocity = 5, force = 8, torque = 11,
                             fluid_force = 14, fluid_torque = 17,
                             contacts = 20, fluid_response = 21,
                             fluid_rotational_response = 22,
                             reference_velocity = 23,
                             reference_angular_velocity = 26,
                             n_properties = 29;
    }

    /// Whole-system numbers of the current state (all ranks agree).
    struct GranularStatistics
    {
      unsigned int n_grains = 0;
      double       kinetic_energy = 0;     ///< translational + rotational (J)
      double       max_overlap = 0;        ///< max delta / R* over contacts
      double       mean_overlap = 0;       ///< mean delta / R*
      double       max_wall_overlap = 0;   ///< max delta / R on walls
      double       coordination = 0;       ///< 2 grain-grain contacts / grain
      double       mean_speed = 0;         ///< m/s
      double       max_speed = 0;          ///< m/s
      double       packing_fraction = 0;   ///< in the probe box
      /// Contact stress in the probe box (Pa, compression positive): the
      /// Love-Weber sum over the grains with the centre inside of the
      /// contact forces times their branch vectors (centre to contact
      /// point), over the box volume, from the last DEM step's forces.
      SymmetricTensor<2, 3> contact_stress;
    };

    /**
     * The in-house DEM: spherical grains carried as particles of a deal.II
     * ParticleHandler on the distributed mesh (so they migrate and are
     * checkpointed with it), moved by velocity Verlet under Hertz-Mindlin
     * contacts (ContactLaw), walls, gravity and a held fluid force.
     *
     * The contact loop runs on flat arrays copied from the particles (local
     * grains first, then the ghost grains of neighbouring ranks) and a
     * Verlet neighbour list built by linked cells of size 2 r_max + skin,
     * both rebuilt only when some grain moved half the skin; between
     * rebuilds only the ghosts' positions and velocities are exchanged.
     * Each rank computes the forces on its own grains, so a contact across
     * ranks is evaluated on both and needs no reverse communication.
     *
     * The mesh's cells must be at least 2 r_max + skin wide wherever grains
     * are (the granular scene builds such a mesh): deal.II's ghost layer of
     * one cell is then the contact halo.
     */
    class GranularDynamics
    {
    public:
      GranularDynamics(parallel::distributed::Triangulation<3> &tria,
                       const DEMParameters                        &parameters,
                       const BoundingBox<3>                       &domain);

      /// Add grains: every rank passes the same list (or rank 0 alone);
      /// each grain goes to the rank owning its cell. Ids follow the list.
      void
      insert(const std::vector<Grain<3>> &grains, const bool from_all_ranks);

      /// Fix the step (from the parameters or the Rayleigh time) and check
      /// it; call after insert().
      void
      initialize();

      /// One velocity-Verlet step. With @p max_duration, the step is
      /// shortened so that whole steps land on current time + max_duration.
      void
      step(const double max_duration = std::numeric_limits<double>::max());

      /// Steps (each stable, the last ones shortened) until the time is
      /// @p end_time: the DEM sub-steps under one fluid step.
      void
      advance_to(const double end_time);

      /**
       * Hold the fluid force and torque on each grain until the next call
       * (the coupled loop's fluid step). Indexed by grain id; every rank
       * passes the whole lists. During the sub-steps the force follows the
       * grain's velocity v linearly, F - K (v - v_n) with v_n the velocity
       * now and K = @p response (N s/m; torque: @p rotational_response,
       * N m s), the fluid's estimated resistance to a change of the
       * grain's velocity: explicit coupling of a held force is unstable
       * when that resistance is large against the grain's inertia over a
       * coupling step. The total force of this step is corrected at once,
       * so the next half kick already sees the new fluid force.
       */
      void
      set_fluid_forces(const std::vector<Tensor<1, 3>> &force,
                       const std::vector<Tensor<1, 3>> &torque,
                       const std::vector<double>       &response,
                       const std::vector<double>       &rotational_response);

      double
      time() const
      {
        return current_time;
      }
      double
      time_step() const
      {
        return dt;
      }
      /// Current step (adaptive steps change it).
      /// Rayleigh time of the smallest grain.
      double
      rayleigh_time() const
      {
        return t_rayleigh;
      }
      unsigned long
      step_number() const
      {
        return n_steps;
      }
      unsigned long
      n_neighbor_list_builds() const
      {
        return n_builds;
      }
      unsigned int
      n_load_balances() const
      {
        return n_balances;
      }
      unsigned int
      n_lost_grains() const
      {
        return lost_grains;
      }

      GranularStatistics
      statistics(const BoundingBox<3> &probe) const;

      /// omega dt and c dt of the stiffest and most damped grain (all ranks)
      /// in the last step: an explicit step is stable for omega dt < 2.
      std::pair<double, double>
      stability_rates() const
      {
        return {Utilities::MPI::max(stiffness_rate, comm),
                Utilities::MPI::max(damping_rate, comm)};
      }

      const std::vector<Wall> &
      get_walls() const
      {
        return walls;
      }

      /// All grains, gathered on every rank, sorted by id; with @p ids, also
      /// their ids (grains that left the domain are missing).
      std::vector<Grain<3>>
      gather_grains(std::vector<types::particle_index> *ids = nullptr) const;

      /// The particles with current properties (for output).
      const Particles::ParticleHandler<3> &
      particles();

      const ContactLaw &
      contact_law() const
      {
        return law;
      }

      /**
       * Write the whole state (grains with ids and forces, contact
       * histories, walls, time and step) to @p out on rank 0; collective.
       * load_state() on a GranularDynamics built with the same parameters
       * (and any number of ranks) continues the run as if uninterrupted.
       */
      void
      save_state(std::ostream &out) const;

      /// Replace initialize(): read the state that save_state() wrote (every
      /// rank reads the same stream).
      void
      load_state(std::istream &in);

    private:
      /// Insert the grains with the given ids and property rows whose
      /// centres lie in this rank's cells.
      void
      insert_local(const std::vector<Point<3>>              &centers,
                   const std::vector<types::particle_index> &ids,
                   const std::vector<std::vector<double>>   &properties);
      /// Grain size range, Verlet skin, Rayleigh time and the (checked)
      /// time step.
      void
      set_up_time_step();
      void
      copy_from_particles();
      void
      copy_to_particles();
      void
      rebuild_neighbor_lists();
      /// Adaptive step: keep max(omega dt, c dt) of the stiffest grain at
      /// dem/contact stability number (below the Rayleigh-based step);
      /// fixed step: stop with a message once it would be unstable.
      void
      adapt_time_step();
      /// Repartition the mesh with cells weighted by their grains when the
      /// grain counts per rank drifted apart (pours pile up at the bottom).
      void
      balance_load();
      void
      update_ghosts();
      /// Contact, body and fluid forces at the current positions and
      /// (predicted end-of-step) velocities; @p v_slide, @p w_slide: the
      /// velocities over the step, which load the tangential springs.
      void
      compute_forces(const std::vector<Tensor<1, 3>> &v_slide,
                     const std::vector<Tensor<1, 3>> &w_slide);
      /// Love-Weber sum over the contacts of the local grains in probe, from
      /// the forces of the last compute_forces().
      Tensor<2, 3>
      contact_virial(const BoundingBox<3> &probe) const;

      const DEMParameters &parameters;
      MPI_Comm             comm;
      const bool           parallel;
      parallel::distributed::Triangulation<3> &triangulation;
      BoundingBox<3>       domain;
      Particles::ParticleHandler<3> particle_handler;
      ContactLaw           law;
      /// The same law with the grain-wall cohesion.
      ContactLaw           wall_law;
      std::vector<Wall>    walls;

      double        dt = 0, t_rayleigh = 0, current_time = 0;
      /// Adaptive stepping and its ceiling (the Rayleigh-based step).
      bool          adaptive = false;
      double        dt_max   = 0;
      unsigned long n_steps = 0, n_builds = 0;
      unsigned int  lost_grains = 0;
      unsigned int  n_balances  = 0;
      double        skin = 0, r_max = 0;

      // Flat state: local grains [0, n_local), then ghosts.
      unsigned int                       n_local = 0;
      std::vector<types::particle_index> id;
      std::vector<Point<3>>              x, x_at_build;
      std::vector<Tensor<1, 3>>          v, w, f, t, f_fluid, t_fluid;
      std::vector<Tensor<1, 3>>          f_old, t_old;
      /// The velocities of the drift (t + dt/2), local grains and ghosts.
      std::vector<Tensor<1, 3>>          v_drift, w_drift;
      /// Linear response of the held fluid force (see set_fluid_forces()).
      std::vector<double>                fluid_response, fluid_rotational_response;
      std::vector<Tensor<1, 3>>          v_reference, w_reference;
      /// Normal damping impulses (N s) that the end-of-step kick adds
      /// (ContactLaw::evaluate()), per local grain.
      std::vector<Tensor<1, 3>>          damping_kick;
      std::vector<double>                radius, mass, inv_mass, inv_inertia;
      std::vector<unsigned int>          n_contacts;
      /// The contact forces of the last compute_forces(), from which
      /// statistics() sums the Love-Weber stress only when asked: force on
      /// grain i of each pair (zero when open; empty after a list build that
      /// no force computation followed), and force on the grain and branch
      /// vector of each grain-wall contact (the walls move after the forces,
      /// so the branch is kept, not recomputed).
      std::vector<Tensor<1, 3>>          pair_force, wall_force, wall_branch;
      /// Sum of the contact stiffnesses and dampings on each grain.
      std::vector<double>                grain_stiffness, grain_damping;
      /// Local max over grains of sqrt(stiffness / m) dt and damping dt / m.
      double stiffness_rate = 0, damping_rate = 0;

      /// Neighbour pairs (i < j in id order of the history) and the history
      /// of each; histories of the grain-wall contacts per local grain.
      std::vector<std::pair<unsigned int, unsigned int>> pairs;
      std::vector<ContactHistory>                        pair_history;
      /// Effective radius and mass of each pair, fixed between rebuilds.
      std::vector<double> pair_r_eff, pair_m_eff;
      /// Grain-wall candidates (local grain, wall) and their histories.
      std::vector<std::pair<unsigned int, unsigned int>> wall_pairs;
      std::vector<ContactHistory>                        wall_history;
      /// Histories read by load_state(), taken up by the next list build
      /// (keys: grain ids, or grain id and wall index).
      std::unordered_map<std::uint64_t, ContactHistory> restored_pairs,
        restored_wall_contacts;
    };

    /**
     * The DEM's home mesh for parallel distribution: the box @p domain in
     * cubes at least @p min_cell_size wide (one contact range, 2 r_max +
     * skin), so that deal.II's ghost-cell layer is the contact halo.
     */
    void
    make_contact_mesh(parallel::distributed::Triangulation<3> &tria,
                      const BoundingBox<3>                    &domain,
                      const double                             min_cell_size);
  } // namespace dem
} // namespace softsand

#endif
