#include <deal.II/base/exceptions.h>

#include <softsand/coupling/held_force_model.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <ostream>

namespace softsand
{
  namespace coupling
  {
    double
    penalty_coupling_number(const double theta,
                            const double fluid_density,
                            const double grain_density,
                            const double cell_edge,
                            const double grain_volume)
    {
      return theta * fluid_density / grain_density * cell_edge * cell_edge *
             cell_edge / grain_volume;
    }


    HeldForceModel::HeldForceModel(const Settings &settings)
      : settings(settings)
    {}


    void
    HeldForceModel::History::resize(const std::size_t n)
    {
      velocity.resize(n);
      force.resize(n);
      angular_velocity.resize(n);
      torque.resize(n);
      resistance.resize(n, 0.);
      rotational_resistance.resize(n, 0.);
    }


    std::vector<double>
    HeldForceModel::clearances(const std::vector<dem::Grain<3>> &grains,
                               const GrainLocator<3>            &locator,
                               const double finest_cell) const
    {
      // Beyond a diameter or a finest cell the gap does not matter.
      std::vector<double>       clearance(grains.size());
      std::vector<unsigned int> near;
      const auto               &lo = settings.box.get_boundary_points().first;
      const auto               &hi = settings.box.get_boundary_points().second;
      for (unsigned int g = 0; g < grains.size(); ++g)
        {
          const auto  &c   = grains[g].center;
          const double r   = grains[g].radius;
          const double cap = std::max(2 * r, finest_cell);
          double      &gap = clearance[g];
          gap              = cap;
          // Faces with an imposed velocity only, as for the fluid's free
          // contact cells: a pressure face holds no layer of fluid against
          // the grain.
          for (unsigned int d = 0; d < 3; ++d)
            {
              if (settings.face_imposes_velocity[2 * d])
                gap = std::min(gap, c[d] - r - lo[d]);
              if (settings.face_imposes_velocity[2 * d + 1])
                gap = std::min(gap, hi[d] - c[d] - r);
            }
          BoundingBox<3> box({c, c});
          box.extend(r + cap);
          locator.grains_near_box(box, near);
          for (const unsigned int k : near)
            if (k != g)
              gap = std::min(gap,
                             c.distance(grains[k].center) - r -
                               grains[k].radius);
        }
      return clearance;
    }


    HeldForces
    HeldForceModel::compute(const std::vector<dem::Grain<3>>          &grains,
                            const std::vector<types::particle_index> &ids,
                            const GrainForces<3>                      &forces,
                            const GrainLocator<3>                     &locator,
                            const double finest_cell,
                            const double dt)
    {
      const double mu        = settings.viscosity;
      const double rho_f     = settings.fluid_density;
      const bool   transient = settings.transient;

      types::particle_index n_ids = 0;
      for (const auto i : ids)
        n_ids = std::max<types::particle_index>(n_ids, i + 1);
      HeldForces held;
      held.force.resize(n_ids);
      held.torque.resize(n_ids);
      held.resistance.resize(n_ids);
      held.rotational_resistance.resize(n_ids);

      std::vector<double> clearance;
      if (transient)
        clearance = clearances(grains, locator, finest_cell);

      for (unsigned int g = 0; g < grains.size(); ++g)
        {
          const auto   i    = ids[g];
          const double d    = grains[g].diameter();
          auto        &k    = held.resistance[i];
          auto        &k_r  = held.rotational_resistance[i];
          held.force[i]     = forces.force[g];
          held.torque[i]    = forces.torque[g];
          if (settings.buoyancy)
            held.force[i] -= rho_f * grains[g].measure() * settings.gravity;
          // Steady Stokes drag; transient fluid: plus the fluid that a
          // change of the grain's velocity must set in motion within the
          // step, the added mass and a shell one viscous diffusion length
          // sqrt(pi nu dt) thick, or one cell where the mesh does not
          // resolve that length.
          k   = 3 * M_PI * mu * d;
          k_r = M_PI * mu * d * d * d;
          if (transient)
            {
              const double shell =
                std::max(finest_cell, std::sqrt(M_PI * mu / rho_f * dt));
              const double shell_mass = rho_f * M_PI * d * d * shell;
              // Rigid nodes: the reaction also carries the inertia of the
              // fluid nodes inside the grain, which follow it: one
              // displaced mass more.
              const double covered = settings.added_mass_coefficient +
                                     (settings.rigid_nodes ? 1. : 0.);
              k += (rho_f * covered * grains[g].measure() + shell_mass) / dt;
              // The shell turns with the grain: its moment of inertia
              // (2/3) m r^2.
              k_r += shell_mass * d * d / 6 / dt;
            }
          // The secants of the last two solves measure the grain's
          // resistance to translation and rotation: crowding, walls and the
          // thin fluid layers of contacts raise it far above the estimates
          // above (a grain on the floor: 4.5x in the transient model, and a
          // held force then overshoots, doubling the jitter each step).
          // Stokes flow is linear in the grain velocities, the transient
          // response nearly so over a step. In the transient model a grain
          // within a diameter of a wall or another grain takes the secant
          // where it is more than twice the estimate (grains crowding in a
          // closed box: their held forces swung 1.4x per step otherwise). A
          // free grain keeps the estimate: its force also follows its
          // acceleration (added mass, history), so the secant overstates
          // the resistance (a free sphere then reached 0.82 U instead of
          // 0.94 U at 0.05 s), and near its steady velocity the secant of
          // ever smaller changes amplifies round-off.
          auto &h = history;
          if (i < h.velocity.size() && h.resistance[i] > 0)
            {
              // Within a finest cell: the thin fluid layer there resists
              // far more than the estimates above. Within a diameter:
              // neighbours and walls may.
              const bool always = !transient || clearance[g] < finest_cell;
              const bool if_larger =
                transient && clearance[g] < 2 * grains[g].radius;
              const auto secant = [always, if_larger](const Tensor<1, 3> &dv,
                                                      const Tensor<1, 3> &dF,
                                                      const Tensor<1, 3> &v,
                                                      const double old,
                                                      const double low) {
                double s = old;
                if (dv.norm() > 1e-2 * v.norm() && dv.norm() > 0 &&
                    dF * dv < 0)
                  s = -(dF * dv) / dv.norm_square();
                s = std::clamp(s, low, 1e4 * low);
                return (always || (if_larger && s > 2 * low)) ? s : low;
              };
              k   = secant(grains[g].velocity - h.velocity[i],
                         forces.force[g] - h.force[i],
                         grains[g].velocity,
                         h.resistance[i],
                         k);
              k_r = secant(grains[g].angular_velocity - h.angular_velocity[i],
                           forces.torque[g] - h.torque[i],
                           grains[g].angular_velocity,
                           h.rotational_resistance[i],
                           k_r);
            }
          if (h.velocity.size() < n_ids)
            h.resize(n_ids);
          h.velocity[i]              = grains[g].velocity;
          h.force[i]                 = forces.force[g];
          h.angular_velocity[i]      = grains[g].angular_velocity;
          h.torque[i]                = forces.torque[g];
          h.resistance[i]            = k;
          h.rotational_resistance[i] = k_r;
        }
      return held;
    }


    void
    HeldForceModel::save(std::ostream &out) const
    {
      const auto &h = history;
      out << h.resistance.size() << '\n';
      for (unsigned int i = 0; i < h.resistance.size(); ++i)
        out << h.velocity[i] << ' ' << h.force[i] << ' '
            << h.angular_velocity[i] << ' ' << h.torque[i] << ' '
            << h.resistance[i] << ' ' << h.rotational_resistance[i] << '\n';
    }


    void
    HeldForceModel::load(std::istream &in, const std::string &source)
    {
      unsigned int n_ids = 0;
      in >> n_ids;
      auto &h = history;
      h     = History();
      h.resize(n_ids);
      for (unsigned int i = 0; i < n_ids && in; ++i)
        {
          for (auto *v :
               {&h.velocity[i], &h.force[i], &h.angular_velocity[i], &h.torque[i]})
            for (unsigned int d = 0; d < 3; ++d)
              in >> (*v)[d];
          in >> h.resistance[i] >> h.rotational_resistance[i];
        }
      AssertThrow(!in.fail(),
                  ExcMessage("The checkpoint <" + source +
                             "> is truncated or corrupt."));
    }
  } // namespace coupling
} // namespace softsand
