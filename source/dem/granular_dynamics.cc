#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/dem/granular_dynamics.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace softsand
{
  namespace dem
  {
    namespace
    {
      const MappingQ1<3> &
      mapping()
      {
        static const MappingQ1<3> m;
        return m;
      }

      /// Where two overlapping grains touch: n the unit normal from j's
      /// centre to i's, delta the overlap, li and lj the distances from
      /// the centres to the contact point (i's at -li n, j's at +lj n).
      /// The one definition for the forces and for the contact stress.
      struct PairGeometry
      {
        Tensor<1, 3> n;
        double       delta, li, lj;
      };

      /// @p d = x_i - x_j, @p d2 its square norm.
      inline PairGeometry
      pair_geometry(const Tensor<1, 3> &d,
                    const double        d2,
                    const double        radius_i,
                    const double        radius_j)
      {
        const double dist  = std::sqrt(d2);
        const double delta = radius_i + radius_j - dist;
        return {(1. / dist) * d,
                delta,
                radius_i - 0.5 * delta,
                radius_j - 0.5 * delta};
      }

      inline std::uint64_t
      pair_key(const types::particle_index a, const types::particle_index b)
      {
        return (static_cast<std::uint64_t>(a) << 32) ^
               static_cast<std::uint64_t>(b);
      }

      inline Tensor<1, 3>
      read_tensor(const ArrayView<const double> &p, const unsigned int first)
      {
        return Tensor<1, 3>({p[first], p[first + 1], p[first + 2]});
      }

      inline void
      write_tensor(const Tensor<1, 3>      &value,
                   const ArrayView<double> &p,
                   const unsigned int       first)
      {
        for (unsigned int d = 0; d < 3; ++d)
          p[first + d] = value[d];
      }

      std::string
      str(const double v)
      {
        std::ostringstream s;
        s << v;
        return s.str();
      }

      /**
       * Contact histories of grains that changed rank. Grain-wall contacts
       * are evaluated only by the grain's owner, and a pair by the owners of
       * its grains: when a grain moves to another rank (or the mesh is
       * repartitioned), its new owner may not have evaluated its contacts
       * before. Each rank publishes the histories of the contacts of the
       * grains that have @p left it, and takes from what the others
       * published those it has none of. Collective; only the grains that
       * changed rank cost communication.
       */
      void
      hand_over_histories(
        const MPI_Comm                                      comm,
        const std::unordered_set<types::particle_index>    &left,
        std::unordered_map<std::uint64_t, ContactHistory> &pair_histories,
        std::unordered_map<std::uint64_t, ContactHistory> &wall_histories)
      {
        // Records of 11 numbers: kind (0 pair, 1 wall), the two halves of
        // the key (grain ids, or grain id and wall), the history.
        constexpr unsigned int size = 11;
        std::vector<double>    published;
        const auto publish = [&](const double          kind,
                                 const std::uint64_t   key,
                                 const ContactHistory &h) {
          published.insert(published.end(),
                           {kind,
                            double(key >> 32),
                            double(key & 0xffffffffu),
                            h.shear[0],
                            h.shear[1],
                            h.shear[2],
                            h.rolling_torque[0],
                            h.rolling_torque[1],
                            h.rolling_torque[2],
                            h.damping_potential,
                            h.damping_force});
        };
        for (const auto &[key, h] : pair_histories)
          if (left.count(key >> 32) > 0 || left.count(key & 0xffffffffu) > 0)
            publish(0, key, h);
        for (const auto &[key, h] : wall_histories)
          if (left.count(key >> 32) > 0)
            publish(1, key, h);

        const auto all = Utilities::MPI::all_gather(comm, published);
        const unsigned int me = Utilities::MPI::this_mpi_process(comm);
        for (unsigned int rank = 0; rank < all.size(); ++rank)
          if (rank != me)
            for (std::size_t k = 0; k + size <= all[rank].size(); k += size)
              {
                const double      *r = &all[rank][k];
                ContactHistory     h;
                h.shear             = Tensor<1, 3>({r[3], r[4], r[5]});
                h.rolling_torque    = Tensor<1, 3>({r[6], r[7], r[8]});
                h.damping_potential = r[9];
                h.damping_force     = r[10];
                const std::uint64_t key =
                  pair_key(static_cast<types::particle_index>(r[1]),
                           static_cast<types::particle_index>(r[2]));
                // A contact this rank evaluated itself keeps its history.
                (r[0] == 0 ? pair_histories : wall_histories).emplace(key, h);
              }
      }
    } // namespace


    GranularDynamics::GranularDynamics(
      parallel::distributed::Triangulation<3> &tria,
      const DEMParameters                         &parameters,
      const BoundingBox<3>                        &domain)
      : parameters(parameters)
      , comm(tria.get_communicator())
      , parallel(Utilities::MPI::n_mpi_processes(comm) > 1)
      , triangulation(tria)
      , domain(domain)
      , particle_handler(tria, mapping(), property::n_properties)
      , law(parameters.material, parameters.rolling_model)
      , wall_law(parameters.material.wall_material(), parameters.rolling_model)
      , walls(create_walls(parameters.walls, domain))
    {
      particle_handler.signals.particle_lost.connect(
        [this](const auto &, const auto &) { ++lost_grains; });
    }


    void
    GranularDynamics::insert(const std::vector<Grain<3>> &grains,
                             const bool                   from_all_ranks)
    {
      // Every rank sees the list (broadcast from rank 0 if only it has
      // one) and keeps the grains in its own cells. Insertion by point
      // location on each rank; deal.II 9.4's insert_global_particles() hangs
      // when some ranks pass no points.
      std::vector<Grain<3>> all = grains;
      if (!from_all_ranks && parallel)
        {
          const auto parts = Utilities::MPI::all_gather(comm, [&]() {
            std::vector<double> flat;
            for (const auto &g : grains)
              {
                for (unsigned int d = 0; d < 3; ++d)
                  flat.push_back(g.center[d]);
                flat.push_back(g.radius);
                for (unsigned int d = 0; d < 3; ++d)
                  flat.push_back(g.velocity[d]);
                for (unsigned int d = 0; d < 3; ++d)
                  flat.push_back(g.angular_velocity[d]);
              }
            return flat;
          }());
          all.clear();
          for (const auto &part : parts)
            for (unsigned int k = 0; k + 10 <= part.size(); k += 10)
              {
                Grain<3> g;
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    g.center[d]           = part[k + d];
                    g.velocity[d]         = part[k + 4 + d];
                    g.angular_velocity[d] = part[k + 7 + d];
                  }
                g.radius = part[k + 3];
                all.push_back(g);
              }
        }
      const types::particle_index first = particle_handler.n_global_particles();
      std::vector<Point<3>>              centers(all.size());
      std::vector<types::particle_index> ids(all.size());
      std::vector<std::vector<double>>   properties(
        all.size(), std::vector<double>(property::n_properties, 0.));
      for (unsigned int g = 0; g < all.size(); ++g)
        {
          centers[g]                        = all[g].center;
          ids[g]                            = first + g;
          std::vector<double> &p            = properties[g];
          p[property::radius]               = all[g].radius;
          p[property::density]              = parameters.material.density;
          for (unsigned int d = 0; d < 3; ++d)
            {
              p[property::velocity + d]         = all[g].velocity[d];
              p[property::angular_velocity + d] = all[g].angular_velocity[d];
            }
        }
      insert_local(centers, ids, properties);
      particle_handler.update_cached_numbers();
      const unsigned int expected = all.size();
      AssertThrow(particle_handler.n_global_particles() == first + expected,
                  ExcMessage("Of " + std::to_string(expected) +
                             " grains, only " +
                             std::to_string(particle_handler.n_global_particles() -
                                            first) +
                             " have their centre inside the mesh box; every "
                             "grain must start inside the domain (and each is inserted "
                             "once)."));
    }


    void
    GranularDynamics::insert_local(
      const std::vector<Point<3>>              &centers,
      const std::vector<types::particle_index> &ids,
      const std::vector<std::vector<double>>   &properties)
    {
      GridTools::Cache<3> cache(triangulation, mapping());
      typename Triangulation<3>::active_cell_iterator hint;
      // Points outside this rank's cells would send the cell search over
      // the whole mesh: skip them by the bounding boxes of the own cells.
      // (Insertion by point location on each rank: deal.II 9.4's
      // insert_global_particles() hangs when some ranks pass no points.)
      auto local_boxes = GridTools::compute_mesh_predicate_bounding_box(
        triangulation, IteratorFilters::LocallyOwnedCell(), 1, false, 4);
      for (auto &box : local_boxes)
        box.extend(1e-10 * std::max(1e-300, box.side_length(0)));
      for (unsigned int g = 0; g < centers.size(); ++g)
        {
          bool near = false;
          for (const auto &box : local_boxes)
            near = near || box.point_inside(centers[g]);
          if (!near)
            continue;
          const auto found =
            GridTools::find_active_cell_around_point(cache, centers[g], hint);
          if (found.first.state() != IteratorState::valid ||
              !found.first->is_locally_owned())
            continue;
          hint = found.first;
          particle_handler.insert_particle(centers[g],
                                           found.second,
                                           ids[g],
                                           found.first,
                                           ArrayView<const double>(properties[g]));
        }
    }


    void
    GranularDynamics::initialize()
    {
      set_up_time_step();
      rebuild_neighbor_lists();
      compute_forces(v, w);
      if (adaptive)
        adapt_time_step();
    }


    void
    GranularDynamics::set_up_time_step()
    {
      double r_min = std::numeric_limits<double>::max();
      r_max        = 0;
      for (const auto &particle : particle_handler)
        {
          const double r = particle.get_properties()[property::radius];
          AssertThrow(r > 0,
                      ExcMessage("Grain " + std::to_string(particle.get_id()) +
                                 " has radius " + str(r) +
                                 " m: radii must be > 0."));
          r_min = std::min(r_min, r);
          r_max = std::max(r_max, r);
        }
      r_min = Utilities::MPI::min(r_min, comm);
      r_max = Utilities::MPI::max(r_max, comm);
      skin  = parameters.skin_fraction * std::max(r_max, 1e-300);

      t_rayleigh = parameters.material.rayleigh_time(r_min);
      if (particle_handler.n_global_particles() == 0)
        t_rayleigh = 0;
      dt = parameters.time_step;
      if (dt == 0)
        {
          AssertThrow(t_rayleigh > 0,
                      ExcMessage("dem/time step = 0 asks for the automatic "
                                 "step, but a scene without grains has no "
                                 "Rayleigh time: set the time step."));
          dt = parameters.automatic_rayleigh_fraction * t_rayleigh;
        }
      else if (t_rayleigh > 0 &&
               dt > parameters.max_rayleigh_fraction * t_rayleigh)
        base::throw_invalid_parameter(
          "dem/time step",
          str(dt),
          "it is " + str(dt / t_rayleigh) +
            " of the Rayleigh time " + str(t_rayleigh) +
            " s of the smallest grain (radius " + str(r_min) +
            " m); the limit 'dem/max rayleigh fraction' is " +
            str(parameters.max_rayleigh_fraction) +
            ": take dt <= " +
            str(parameters.max_rayleigh_fraction * t_rayleigh) +
            " s or 0 for the automatic step");

      adaptive = (parameters.time_step == 0);
      dt_max   = dt;
    }


    void
    GranularDynamics::copy_from_particles()
    {
      n_local                  = particle_handler.n_locally_owned_particles();
      const unsigned int total = n_local + (parallel ? std::distance(
                                                         particle_handler.begin_ghost(),
                                                         particle_handler.end_ghost()) :
                                                       0);
      id.resize(total);
      x.resize(total);
      for (auto *a : {&v, &w, &f, &t, &f_fluid, &t_fluid, &v_reference, &w_reference})
        a->resize(total);
      fluid_response.resize(total);
      fluid_rotational_response.resize(total);
      radius.resize(total);
      mass.resize(total);
      inv_mass.resize(total);
      inv_inertia.resize(total);
      n_contacts.assign(total, 0);

      const auto read = [&](const auto &particle, const unsigned int i) {
        const ArrayView<const double> p = particle.get_properties();
        id[i]     = particle.get_id();
        x[i]      = particle.get_location();
        radius[i] = p[property::radius];
        mass[i]   = p[property::density] * 4. / 3. * M_PI * std::pow(radius[i], 3);
        inv_mass[i]    = 1. / mass[i];
        inv_inertia[i] = 1. / (0.4 * mass[i] * radius[i] * radius[i]);
        v[i]       = read_tensor(p, property::velocity);
        w[i]       = read_tensor(p, property::angular_velocity);
        f[i]       = read_tensor(p, property::force);
        t[i]       = read_tensor(p, property::torque);
        f_fluid[i] = read_tensor(p, property::fluid_force);
        t_fluid[i] = read_tensor(p, property::fluid_torque);
        v_reference[i] = read_tensor(p, property::reference_velocity);
        w_reference[i] = read_tensor(p, property::reference_angular_velocity);
        fluid_response[i]            = p[property::fluid_response];
        fluid_rotational_response[i] = p[property::fluid_rotational_response];
      };
      unsigned int i = 0;
      for (const auto &particle : particle_handler)
        read(particle, i++);
      if (parallel)
        for (auto it = particle_handler.begin_ghost();
             it != particle_handler.end_ghost();
             ++it)
          read(*it, i++);
    }


    void
    GranularDynamics::copy_to_particles()
    {
      unsigned int i = 0;
      for (auto &particle : particle_handler)
        {
          particle.set_location(x[i]);
          const ArrayView<double> p = particle.get_properties();
          write_tensor(v[i], p, property::velocity);
          write_tensor(w[i], p, property::angular_velocity);
          write_tensor(f[i], p, property::force);
          write_tensor(t[i], p, property::torque);
          write_tensor(f_fluid[i], p, property::fluid_force);
          write_tensor(t_fluid[i], p, property::fluid_torque);
          write_tensor(v_reference[i], p, property::reference_velocity);
          write_tensor(w_reference[i], p, property::reference_angular_velocity);
          p[property::fluid_response]            = fluid_response[i];
          p[property::fluid_rotational_response] = fluid_rotational_response[i];
          p[property::contacts] = n_contacts[i];
          ++i;
        }
    }


    void
    GranularDynamics::update_ghosts()
    {
      copy_to_particles();
      particle_handler.update_ghost_particles();
      unsigned int i = n_local;
      for (auto it = particle_handler.begin_ghost();
           it != particle_handler.end_ghost();
           ++it, ++i)
        {
          const ArrayView<const double> p = it->get_properties();
          x[i] = it->get_location();
          v[i] = read_tensor(p, property::velocity);
          w[i] = read_tensor(p, property::angular_velocity);
          f[i] = read_tensor(p, property::force);
          t[i] = read_tensor(p, property::torque);
        }
    }


    void
    GranularDynamics::rebuild_neighbor_lists()
    {
      // Remember the histories of open contacts by grain ids.
      std::unordered_map<std::uint64_t, ContactHistory> old_pairs;
      old_pairs.reserve(pairs.size());
      for (unsigned int k = 0; k < pairs.size(); ++k)
        if (pair_history[k].shear.norm_square() > 0 ||
            pair_history[k].rolling_torque.norm_square() > 0 ||
            pair_history[k].damping_potential > 0)
          old_pairs.emplace(pair_key(id[pairs[k].first], id[pairs[k].second]),
                            pair_history[k]);
      old_pairs.merge(restored_pairs);
      restored_pairs.clear();
      std::unordered_map<std::uint64_t, ContactHistory> old_wall_contacts;
      old_wall_contacts.merge(restored_wall_contacts);
      restored_wall_contacts.clear();
      for (unsigned int k = 0; k < wall_pairs.size(); ++k)
        if (wall_history[k].shear.norm_square() > 0 ||
            wall_history[k].rolling_torque.norm_square() > 0 ||
            wall_history[k].damping_potential > 0)
          old_wall_contacts.emplace(pair_key(id[wall_pairs[k].first],
                                             wall_pairs[k].second),
                                    wall_history[k]);

      std::unordered_set<types::particle_index> left;
      if (parallel)
        left.insert(id.begin(), id.begin() + n_local);

      if (!x.empty())
        copy_to_particles();
      particle_handler.sort_particles_into_subdomains_and_cells();
      if (parallel)
        balance_load();
      if (parallel)
        particle_handler.exchange_ghost_particles(true);
      copy_from_particles();
      x_at_build = x;
      if (parallel)
        {
          for (unsigned int i = 0; i < n_local; ++i)
            left.erase(id[i]);
          hand_over_histories(comm, left, old_pairs, old_wall_contacts);
        }
      ++n_builds;

      // Linked cells of size 2 r_max + skin over local and ghost grains.
      const unsigned int total = x.size();
      pairs.clear();
      if (total > 0)
        {
          Point<3> lo = x[0], hi = x[0];
          for (const auto &p : x)
            for (unsigned int d = 0; d < 3; ++d)
              {
                lo[d] = std::min(lo[d], p[d]);
                hi[d] = std::max(hi[d], p[d]);
              }
          double size = 2 * r_max + skin;
          std::array<unsigned int, 3> n_cells;
          for (;;)
            {
              std::size_t product = 1;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  n_cells[d] = 1 + static_cast<unsigned int>((hi[d] - lo[d]) / size);
                  product *= n_cells[d];
                }
              if (product <= 8 * std::size_t(total) + 64)
                break;
              size *= 1.5; // sparse grains: fewer, larger cells
            }
          const auto cell_of = [&](const Point<3> &p) {
            unsigned int c[3];
            for (unsigned int d = 0; d < 3; ++d)
              c[d] = std::min(n_cells[d] - 1,
                              static_cast<unsigned int>((p[d] - lo[d]) / size));
            return (c[2] * n_cells[1] + c[1]) * n_cells[0] + c[0];
          };
          const unsigned int n_all = n_cells[0] * n_cells[1] * n_cells[2];
          std::vector<unsigned int> start(n_all + 1, 0), cell(total), order(total);
          for (unsigned int i = 0; i < total; ++i)
            {
              cell[i] = cell_of(x[i]);
              ++start[cell[i] + 1];
            }
          for (unsigned int c = 0; c < n_all; ++c)
            start[c + 1] += start[c];
          {
            std::vector<unsigned int> fill(start.begin(), start.end() - 1);
            for (unsigned int i = 0; i < total; ++i)
              order[fill[cell[i]]++] = i;
          }
          for (unsigned int i = 0; i < total; ++i)
            {
              const unsigned int c  = cell[i];
              const int          cx = c % n_cells[0];
              const int          cy = (c / n_cells[0]) % n_cells[1];
              const int          cz = c / (n_cells[0] * n_cells[1]);
              for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                  for (int dx = -1; dx <= 1; ++dx)
                    {
                      const int nx = cx + dx, ny = cy + dy, nz = cz + dz;
                      if (nx < 0 || ny < 0 || nz < 0 ||
                          nx >= int(n_cells[0]) || ny >= int(n_cells[1]) ||
                          nz >= int(n_cells[2]))
                        continue;
                      const unsigned int nc =
                        (nz * n_cells[1] + ny) * n_cells[0] + nx;
                      for (unsigned int k = start[nc]; k < start[nc + 1]; ++k)
                        {
                          const unsigned int j = order[k];
                          if (j <= i || (i >= n_local && j >= n_local))
                            continue;
                          const double reach = radius[i] + radius[j] + skin;
                          if (x[i].distance_square(x[j]) < reach * reach)
                            {
                              if (id[i] < id[j])
                                pairs.emplace_back(i, j);
                              else
                                pairs.emplace_back(j, i);
                            }
                        }
                    }
            }
          // The pairs come out ordered by their smaller grain index (the
          // outer loop), so memory order follows the grains.
        }
      pair_history.assign(pairs.size(), ContactHistory());
      // No forces for the new lists (the grains may come in a new order)
      // until the next compute_forces(): a restart reports zero contact
      // stress until its first step.
      pair_force.clear();
      wall_force.clear();
      pair_r_eff.resize(pairs.size());
      pair_m_eff.resize(pairs.size());
      for (unsigned int k = 0; k < pairs.size(); ++k)
        {
          const unsigned int i = pairs[k].first, j = pairs[k].second;
          pair_r_eff[k] = radius[i] * radius[j] / (radius[i] + radius[j]);
          pair_m_eff[k] = mass[i] * mass[j] / (mass[i] + mass[j]);
        }
      if (!old_pairs.empty())
        for (unsigned int k = 0; k < pairs.size(); ++k)
          {
            const auto it =
              old_pairs.find(pair_key(id[pairs[k].first], id[pairs[k].second]));
            if (it != old_pairs.end())
              pair_history[k] = it->second;
          }
      // Grain-wall candidates: local grains within reach of each wall.
      wall_pairs.clear();
      for (unsigned int k = 0; k < walls.size(); ++k)
        {
          walls[k].point_at_build = walls[k].point;
          for (unsigned int i = 0; i < n_local; ++i)
            {
              Tensor<1, 3> n;
              if (walls[k].overlap(x[i], radius[i] + skin, n) > 0)
                wall_pairs.emplace_back(i, k);
            }
        }
      wall_history.assign(wall_pairs.size(), ContactHistory());
      if (!old_wall_contacts.empty())
        for (unsigned int k = 0; k < wall_pairs.size(); ++k)
          {
            const auto it = old_wall_contacts.find(
              pair_key(id[wall_pairs[k].first], wall_pairs[k].second));
            if (it != old_wall_contacts.end())
              wall_history[k] = it->second;
          }
    }


    void
    GranularDynamics::adapt_time_step()
    {
      double rates[2] = {stiffness_rate, damping_rate};
      // A fixed step needs no agreement between ranks: check locally (a
      // failing rank stops the job), no collective per step.
      if (parallel && adaptive)
        Utilities::MPI::max(ArrayView<const double>(rates, 2),
                            comm,
                            ArrayView<double>(rates, 2));
      const double number = std::max(rates[0], rates[1]);
      if (adaptive)
        {
          const double limit = parameters.stability_number;
          dt = (number > 0) ? std::min(dt_max, dt * limit / number) : dt_max;
        }
      else if (number > 2)
        AssertThrow(false,
                    ExcMessage(
                      "At t = " + str(current_time) +
                      " s the contacts have stiffened beyond what dem/time "
                      "step = " + str(dt) +
                      " s can integrate: omega dt = " + str(rates[0]) +
                      ", c dt = " + str(rates[1]) +
                      " for the stiffest grain (explicit steps are unstable "
                      "above 2). Hertz contacts stiffen with the overlap, "
                      "which cohesion or high pressure make large. Take dt "
                      "<= " + str(dt * parameters.stability_number / number) +
                      " s, or time step = 0 to adapt it."));
    }


    void
    GranularDynamics::balance_load()
    {
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const double       mine    = particle_handler.n_locally_owned_particles();
      const double       most    = Utilities::MPI::max(mine, comm);
      const double       mean    = Utilities::MPI::sum(mine, comm) / n_ranks;
      if (most <= 1.1 * mean + 16)
        return;
      // A grain costs far more per step than an empty cell.
      auto connection = triangulation.signals.weight.connect(
        [this](const typename Triangulation<3>::cell_iterator &cell,
               const typename Triangulation<3>::CellStatus     status)
          -> unsigned int {
          if (status == Triangulation<3>::CELL_PERSIST ||
              status == Triangulation<3>::CELL_REFINE)
            return 1 + 20 * particle_handler.n_particles_in_cell(cell);
          return 1;
        });
      particle_handler.prepare_for_coarsening_and_refinement();
      triangulation.repartition();
      particle_handler.unpack_after_coarsening_and_refinement();
      connection.disconnect();
      ++n_balances;
    }


    void
    GranularDynamics::compute_forces(const std::vector<Tensor<1, 3>> &v_slide,
                                     const std::vector<Tensor<1, 3>> &w_slide)
    {
      const Tensor<1, 3> &g = parameters.gravity;
      damping_kick.assign(n_local, Tensor<1, 3>());
      grain_stiffness.assign(x.size(), 0.);
      grain_damping.assign(x.size(), 0.);
      for (unsigned int i = 0; i < n_local; ++i)
        {
          f[i] = mass[i] * g + f_fluid[i] -
                 fluid_response[i] * (v[i] - v_reference[i]);
          t[i] = t_fluid[i] -
                 fluid_rotational_response[i] * (w[i] - w_reference[i]);
          n_contacts[i]     = 0;
          grain_damping[i]  = fluid_response[i];
        }
      pair_force.resize(pairs.size());
      wall_force.resize(wall_pairs.size());
      wall_branch.resize(wall_pairs.size());
      const bool cohesive = parameters.material.cohesion_energy_density > 0;
      const bool wall_cohesive = parameters.material.wall_cohesion() > 0;

      Tensor<1, 3> force, torque_i, torque_j;
      for (unsigned int k = 0; k < pairs.size(); ++k)
        {
          const unsigned int i   = pairs[k].first;
          const unsigned int j   = pairs[k].second;
          const Tensor<1, 3> d   = x[i] - x[j];
          const double       rs  = radius[i] + radius[j];
          const double       d2  = d.norm_square();
          ContactHistory    &h   = pair_history[k];
          if (d2 >= rs * rs)
            {
              if (h.damping_potential > 0)
                {
                  // Opened during the step: its damping impulse since the
                  // last step returns to zero.
                  const Tensor<1, 3> kick =
                    (law.separation_impulse(h, dt) / std::sqrt(d2)) * d;
                  if (i < n_local)
                    damping_kick[i] += kick;
                  if (j < n_local)
                    damping_kick[j] -= kick;
                }
              h.clear();
              pair_force[k] = Tensor<1, 3>();
              continue;
            }
          const auto [n, delta, li, lj] =
            pair_geometry(d, d2, radius[i], radius[j]);
          const double       r_eff = pair_r_eff[k];
          const double       m_eff = pair_m_eff[k];
          const Tensor<1, 3> v_rel =
            v[i] - v[j] - cross_product_3d(li * w[i] + lj * w[j], n);
          const Tensor<1, 3> v_slide_rel =
            v_slide[i] - v_slide[j] -
            cross_product_3d(li * w_slide[i] + lj * w_slide[j], n);
          double area = 0;
          if (cohesive)
            {
              const double ri2 = radius[i] * radius[i], rj2 = radius[j] * radius[j];
              const double s   = d2 - rj2 + ri2;
              area = M_PI * std::max(0., (4 * d2 * ri2 - s * s) / (4 * d2));
            }
          double stiffness, damping, impulse;
          law.evaluate(n, delta, li, lj, r_eff, m_eff, v_rel, v_slide_rel, w[i] - w[j],
                       area, dt, h, force, torque_i, torque_j, stiffness,
                       damping, impulse);
          grain_stiffness[i] += stiffness;
          grain_stiffness[j] += stiffness;
          grain_damping[i] += damping;
          grain_damping[j] += damping;
          pair_force[k] = force;
          if (i < n_local)
            {
              f[i] += force;
              t[i] += torque_i;
              damping_kick[i] += impulse * n;
              ++n_contacts[i];
            }
          if (j < n_local)
            {
              f[j] -= force;
              t[j] += torque_j;
              damping_kick[j] -= impulse * n;
              ++n_contacts[j];
            }
        }

      for (auto &wall : walls)
        {
          wall.force        = 0;
          wall.normal_force = 0;
        }
      for (unsigned int k = 0; k < wall_pairs.size(); ++k)
        {
          const unsigned int i    = wall_pairs[k].first;
          Wall              &wall = walls[wall_pairs[k].second];
          Tensor<1, 3>       n;
          const double       delta = wall.overlap(x[i], radius[i], n);
          ContactHistory    &h     = wall_history[k];
          if (delta <= 0)
            {
              if (h.damping_potential > 0)
                damping_kick[i] += wall_law.separation_impulse(h, dt) * n;
              h.clear();
              wall_force[k] = Tensor<1, 3>();
              continue;
            }
          const double       li    = radius[i] - 0.5 * delta;
          const Tensor<1, 3> v_rel =
            v[i] - wall.velocity - cross_product_3d(li * w[i], n);
          const Tensor<1, 3> v_slide_rel =
            v_slide[i] - wall.velocity - cross_product_3d(li * w_slide[i], n);
          const double area =
            wall_cohesive ? M_PI * delta * (2 * radius[i] - delta) : 0.;
          double stiffness, damping, impulse;
          wall_law.evaluate(n, delta, li, 0., radius[i], mass[i], v_rel, v_slide_rel, w[i],
                       area, dt, h, force, torque_i, torque_j, stiffness,
                       damping, impulse);
          grain_stiffness[i] += stiffness;
          grain_damping[i] += damping;
          damping_kick[i] += impulse * n;
          f[i] += force;
          t[i] += torque_i;
          // n points from the wall into the grain.
          wall_force[k]  = force;
          wall_branch[k] = li * n;
          wall.force -= force;
          wall.normal_force += force * n;
        }

      // Explicit stability: omega dt and c dt of the stiffest grain. Hertz
      // contacts stiffen with the overlap (as sqrt(delta)), so cohesion or
      // high pressure can make them much stiffer than the Rayleigh time
      // assumes.
      double omega2 = 0, rate = 0;
      for (unsigned int i = 0; i < n_local; ++i)
        {
          omega2 = std::max(omega2, grain_stiffness[i] * inv_mass[i]);
          rate   = std::max(rate, grain_damping[i] * inv_mass[i]);
          // The fluid's rotational resistance damps the spin explicitly too.
          if (i < fluid_rotational_response.size())
            rate = std::max(rate,
                            fluid_rotational_response[i] * inv_inertia[i]);
        }
      stiffness_rate = std::sqrt(omega2) * dt;
      damping_rate   = rate * dt;
    }


    void
    GranularDynamics::advance_to(const double end_time)
    {
      const double tolerance = 1e-9 * std::max(dt, 1e-300);
      while (current_time < end_time - tolerance)
        step(end_time - current_time);
    }


    void
    GranularDynamics::set_fluid_forces(
      const std::vector<Tensor<1, 3>> &force,
      const std::vector<Tensor<1, 3>> &torque,
      const std::vector<double>       &response,
      const std::vector<double>       &rotational_response)
    {
      for (unsigned int i = 0; i < n_local; ++i)
        {
          AssertThrow(id[i] < force.size() && id[i] < torque.size() &&
                        id[i] < response.size() &&
                        id[i] < rotational_response.size(),
                      ExcMessage("Fluid forces given for " +
                                 std::to_string(force.size()) +
                                 " grains, but grain id " +
                                 std::to_string(id[i]) + " exists."));
          // Replace the old fluid force in this step's total by the new one
          // (whose velocity reference is the velocity now).
          f[i] += force[id[i]] -
                  (f_fluid[i] - fluid_response[i] * (v[i] - v_reference[i]));
          t[i] += torque[id[i]] -
                  (t_fluid[i] -
                   fluid_rotational_response[i] * (w[i] - w_reference[i]));
          f_fluid[i]                   = force[id[i]];
          t_fluid[i]                   = torque[id[i]];
          fluid_response[i]            = response[id[i]];
          fluid_rotational_response[i] = rotational_response[id[i]];
          v_reference[i]               = v[i];
          w_reference[i]               = w[i];
        }
    }


    void
    GranularDynamics::step(const double max_duration)
    {
      adapt_time_step();
      // Land on the end of the interval in equal steps, none above the
      // stable one; a fixed step is restored afterwards.
      const double nominal_dt = dt;
      if (max_duration < std::numeric_limits<double>::max())
        {
          const double n = std::max(1., std::ceil(max_duration / dt - 1e-9));
          dt = max_duration / n;
        }
      const double half = 0.5 * dt;
      double       max_move2 = 0;
      // Kick, drift, then predict the end-of-step velocity with the old
      // force (v + dt/2 a_n): the damping then sees a second-order velocity
      // instead of the half-step one (the tangential spring is loaded by
      // the drift velocity, the contact point's exact slide); the final
      // kick corrects with the new force, and puts the normal damping
      // impulse of the step at Gamma(delta_new) - Gamma(delta_old) exactly
      // (ContactLaw): restitution then stays within 0.7% of the input for
      // e >= 0.1 at 0.2 T_R, wherever in a step a contact starts.
      for (unsigned int i = 0; i < n_local; ++i)
        {
          v[i] += (half * inv_mass[i]) * f[i];
          w[i] += (half * inv_inertia[i]) * t[i];
          x[i] += dt * v[i];
          max_move2 = std::max(max_move2, x[i].distance_square(x_at_build[i]));
        }
      current_time += dt;
      ++n_steps;

      // Moving walls count like grains: their candidate lists must stay
      // valid too (every rank moves the walls identically).
      for (const auto &wall : walls)
        max_move2 = std::max(max_move2, wall.point.distance_square(wall.point_at_build));
      const bool rebuild =
        (parallel ? Utilities::MPI::max(max_move2, comm) : max_move2) >
        0.25 * skin * skin;
      if (rebuild)
        rebuild_neighbor_lists();
      else if (parallel)
        update_ghosts();
      // After a rebuild the grains may be in a new order (and new ghosts
      // came): predict from the arrays as they are now.
      const unsigned int n_all = x.size();
      v_drift.assign(v.begin(), v.begin() + n_all);
      w_drift.assign(w.begin(), w.begin() + n_all);
      for (unsigned int i = 0; i < n_all; ++i)
        {
          v[i] += (half * inv_mass[i]) * f[i];
          w[i] += (half * inv_inertia[i]) * t[i];
        }
      f_old.assign(f.begin(), f.begin() + n_local);
      t_old.assign(t.begin(), t.begin() + n_local);

      compute_forces(v_drift, w_drift);
      for (unsigned int i = 0; i < n_local; ++i)
        {
          v[i] += (half * inv_mass[i]) * (f[i] - f_old[i]) +
                  inv_mass[i] * damping_kick[i];
          w[i] += (half * inv_inertia[i]) * (t[i] - t_old[i]);
        }

      if (!walls.empty())
        {
          if (parallel)
            {
              std::vector<double> forces(4 * walls.size());
              for (unsigned int k = 0; k < walls.size(); ++k)
                {
                  for (unsigned int d = 0; d < 3; ++d)
                    forces[4 * k + d] = walls[k].force[d];
                  forces[4 * k + 3] = walls[k].normal_force;
                }
              Utilities::MPI::sum(forces, comm, forces);
              for (unsigned int k = 0; k < walls.size(); ++k)
                {
                  for (unsigned int d = 0; d < 3; ++d)
                    walls[k].force[d] = forces[4 * k + d];
                  walls[k].normal_force = forces[4 * k + 3];
                }
            }
          for (auto &wall : walls)
            wall.advance(dt);
        }
      if (!adaptive)
        dt = nominal_dt;
    }


    GranularStatistics
    GranularDynamics::statistics(const BoundingBox<3> &probe) const
    {
      GranularStatistics s;
      double sums[7] = {0, 0, 0, 0, 0, 0, 0}; // ke, overlap, count, speed, volume, n, contacts
      double max_overlap = 0, max_speed = 0;
      for (unsigned int i = 0; i < n_local; ++i)
        {
          const double inertia = 1. / inv_inertia[i];
          sums[0] += 0.5 * mass[i] * v[i].norm_square() +
                     0.5 * inertia * w[i].norm_square();
          const double speed = v[i].norm();
          sums[3] += speed;
          max_speed = std::max(max_speed, speed);
          if (probe.point_inside(x[i]))
            sums[4] += 4. / 3. * M_PI * std::pow(radius[i], 3);
          sums[5] += 1;
        }
      for (unsigned int k = 0; k < pairs.size(); ++k)
        {
          const unsigned int i = pairs[k].first, j = pairs[k].second;
          // A pair across ranks is seen twice: count it where the first
          // grain (lower id) is local.
          if (i >= n_local)
            continue;
          const double rs    = radius[i] + radius[j];
          const double delta = rs - x[i].distance(x[j]);
          if (delta <= 0)
            continue;
          const double ratio = delta / (radius[i] * radius[j] / rs);
          sums[1] += ratio;
          sums[2] += 1;
          max_overlap = std::max(max_overlap, ratio);
        }
      double max_wall_overlap = 0;
      for (unsigned int k = 0; k < wall_pairs.size(); ++k)
        {
          Tensor<1, 3>       n;
          const unsigned int i     = wall_pairs[k].first;
          const double       delta = walls[wall_pairs[k].second].overlap(x[i], radius[i], n);
          max_wall_overlap = std::max(max_wall_overlap, delta / radius[i]);
        }
      s.max_wall_overlap = Utilities::MPI::max(max_wall_overlap, comm);
      Utilities::MPI::sum(ArrayView<const double>(sums, 7),
                          comm,
                          ArrayView<double>(sums, 7));
      s.n_grains       = static_cast<unsigned int>(std::round(sums[5]));
      s.kinetic_energy = sums[0];
      s.mean_overlap   = sums[2] > 0 ? sums[1] / sums[2] : 0;
      s.max_overlap    = Utilities::MPI::max(max_overlap, comm);
      s.coordination   = s.n_grains > 0 ? 2 * sums[2] / s.n_grains : 0;
      s.mean_speed     = s.n_grains > 0 ? sums[3] / s.n_grains : 0;
      s.max_speed      = Utilities::MPI::max(max_speed, comm);
      s.packing_fraction = sums[4] / probe.volume();
      Tensor<2, 3> virial = contact_virial(probe);
      virial = Utilities::MPI::sum(virial, comm);
      // Compression pushes the grain away from the contact: force and
      // branch vector opposed, hence the minus sign.
      s.contact_stress = -symmetrize(virial) / probe.volume();
      return s;
    }


    Tensor<2, 3>
    GranularDynamics::contact_virial(const BoundingBox<3> &probe) const
    {
      // Sum over the contacts of the local grains inside the probe of
      // branch vector (x) force, from the forces of the last
      // compute_forces(). The grains have not moved since, so each pair's
      // branch vectors are recomputed as compute_forces() had them
      // (pair_geometry); the force on j is -force.
      Tensor<2, 3> virial;
      if (pair_force.size() == pairs.size())
        for (unsigned int k = 0; k < pairs.size(); ++k)
          {
            const Tensor<1, 3> &force = pair_force[k];
            if (force.norm_square() == 0)
              continue;
            const unsigned int i = pairs[k].first, j = pairs[k].second;
            const bool in_i = i < n_local && probe.point_inside(x[i]);
            const bool in_j = j < n_local && probe.point_inside(x[j]);
            if (!in_i && !in_j)
              continue;
            const Tensor<1, 3> d = x[i] - x[j];
            const PairGeometry c =
              pair_geometry(d, d.norm_square(), radius[i], radius[j]);
            if (in_i)
              virial -= c.li * outer_product(force, c.n);
            if (in_j)
              virial -= c.lj * outer_product(force, c.n);
          }
      if (wall_force.size() == wall_pairs.size())
        for (unsigned int k = 0; k < wall_pairs.size(); ++k)
          if (probe.point_inside(x[wall_pairs[k].first]))
            // The branch is li n, n from the wall into the grain.
            virial -= outer_product(wall_force[k], wall_branch[k]);
      return virial;
    }


    std::vector<Grain<3>>
    GranularDynamics::gather_grains(std::vector<types::particle_index> *ids) const
    {
      std::vector<double> local;
      for (unsigned int i = 0; i < n_local; ++i)
        {
          local.push_back(id[i]);
          for (unsigned int d = 0; d < 3; ++d)
            local.push_back(x[i][d]);
          local.push_back(radius[i]);
          for (unsigned int d = 0; d < 3; ++d)
            local.push_back(v[i][d]);
          for (unsigned int d = 0; d < 3; ++d)
            local.push_back(w[i][d]);
        }
      const auto all = Utilities::MPI::all_gather(comm, local);
      std::vector<std::pair<double, Grain<3>>> grains;
      for (const auto &part : all)
        for (unsigned int k = 0; k + 10 < part.size() + 1; k += 11)
          {
            Grain<3> g;
            for (unsigned int d = 0; d < 3; ++d)
              {
                g.center[d]           = part[k + 1 + d];
                g.velocity[d]         = part[k + 5 + d];
                g.angular_velocity[d] = part[k + 8 + d];
              }
            g.radius = part[k + 4];
            grains.emplace_back(part[k], g);
          }
      std::sort(grains.begin(), grains.end(), [](const auto &a, const auto &b) {
        return a.first < b.first;
      });
      std::vector<Grain<3>> result;
      if (ids != nullptr)
        ids->clear();
      for (const auto &g : grains)
        {
          result.push_back(g.second);
          if (ids != nullptr)
            ids->push_back(static_cast<types::particle_index>(g.first));
        }
      return result;
    }


    const Particles::ParticleHandler<3> &
    GranularDynamics::particles()
    {
      copy_to_particles();
      return particle_handler;
    }


    // State file: a header of scalars, the walls, the grains, then the
    // contact histories; doubles in binary, so the restart is exact.
    namespace
    {
      void
      write_doubles(std::ostream &out, const std::vector<double> &values)
      {
        const std::uint64_t n = values.size();
        out.write(reinterpret_cast<const char *>(&n), sizeof(n));
        out.write(reinterpret_cast<const char *>(values.data()),
                  n * sizeof(double));
      }

      std::vector<double>
      read_doubles(std::istream &in)
      {
        std::uint64_t n = 0;
        in.read(reinterpret_cast<char *>(&n), sizeof(n));
        AssertThrow(in.good() && n < (std::uint64_t(1) << 40),
                    ExcMessage("The DEM checkpoint is truncated or corrupt."));
        std::vector<double> values(n);
        in.read(reinterpret_cast<char *>(values.data()), n * sizeof(double));
        AssertThrow(in.good(),
                    ExcMessage("The DEM checkpoint is truncated or corrupt."));
        return values;
      }

      constexpr unsigned int grain_record = 1 + 3 + property::n_properties;
      constexpr unsigned int history_record = 2 + 8;
    } // namespace


    void
    GranularDynamics::save_state(std::ostream &out) const
    {
      // Grains: id, position, all properties (forces included: velocity
      // Verlet's first half kick uses the force of the last step).
      std::vector<double> grains_local, pairs_local, walls_local;
      for (unsigned int i = 0; i < n_local; ++i)
        {
          grains_local.push_back(id[i]);
          for (unsigned int d = 0; d < 3; ++d)
            grains_local.push_back(x[i][d]);
          std::vector<double> p(property::n_properties, 0.);
          p[property::radius]  = radius[i];
          p[property::density] = mass[i] / (4. / 3. * M_PI * std::pow(radius[i], 3));
          const std::pair<unsigned int, const Tensor<1, 3> *> vectors[] = {
            {property::velocity, &v[i]},
            {property::angular_velocity, &w[i]},
            {property::force, &f[i]},
            {property::torque, &t[i]},
            {property::fluid_force, &f_fluid[i]},
            {property::fluid_torque, &t_fluid[i]},
            {property::reference_velocity, &v_reference[i]},
            {property::reference_angular_velocity, &w_reference[i]}};
          p[property::fluid_response]            = fluid_response[i];
          p[property::fluid_rotational_response] = fluid_rotational_response[i];
          for (const auto &[first, value] : vectors)
            for (unsigned int d = 0; d < 3; ++d)
              p[first + d] = (*value)[d];
          p[property::contacts] = n_contacts[i];
          grains_local.insert(grains_local.end(), p.begin(), p.end());
        }
      const auto add_history = [](std::vector<double>  &list,
                                  const double          a,
                                  const double          b,
                                  const ContactHistory &h) {
        if (h.shear.norm_square() == 0 && h.rolling_torque.norm_square() == 0 &&
            h.damping_potential == 0 && h.damping_force == 0)
          return;
        list.push_back(a);
        list.push_back(b);
        for (unsigned int d = 0; d < 3; ++d)
          list.push_back(h.shear[d]);
        for (unsigned int d = 0; d < 3; ++d)
          list.push_back(h.rolling_torque[d]);
        list.push_back(h.damping_potential);
        list.push_back(h.damping_force);
      };
      // A pair across ranks is held by both with the same history: keep
      // the copy of the rank owning its first grain.
      for (unsigned int k = 0; k < pairs.size(); ++k)
        if (pairs[k].first < n_local)
          add_history(pairs_local,
                      id[pairs[k].first],
                      id[pairs[k].second],
                      pair_history[k]);
      for (unsigned int k = 0; k < wall_pairs.size(); ++k)
        add_history(walls_local,
                    id[wall_pairs[k].first],
                    wall_pairs[k].second,
                    wall_history[k]);

      const auto gather = [&](const std::vector<double> &local) {
        std::vector<double> all;
        for (const auto &part : Utilities::MPI::gather(comm, local, 0))
          all.insert(all.end(), part.begin(), part.end());
        return all;
      };
      const std::vector<double> grains_all = gather(grains_local);
      const std::vector<double> pairs_all  = gather(pairs_local);
      const std::vector<double> walls_all  = gather(walls_local);
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;

      std::vector<double> header = {current_time,
                                    dt,
                                    double(n_steps),
                                    double(n_builds),
                                    double(lost_grains),
                                    stiffness_rate,
                                    damping_rate,
                                    double(walls.size())};
      write_doubles(out, header);
      std::vector<double> wall_state;
      for (const auto &wall : walls)
        {
          for (unsigned int d = 0; d < 3; ++d)
            wall_state.push_back(wall.point[d]);
          for (unsigned int d = 0; d < 3; ++d)
            wall_state.push_back(wall.velocity[d]);
          for (unsigned int d = 0; d < 3; ++d)
            wall_state.push_back(wall.force[d]);
          wall_state.push_back(wall.error_integral);
        }
      write_doubles(out, wall_state);
      write_doubles(out, grains_all);
      write_doubles(out, pairs_all);
      write_doubles(out, walls_all);
    }


    void
    GranularDynamics::load_state(std::istream &in)
    {
      const std::vector<double> header = read_doubles(in);
      AssertThrow(header.size() == 8 && header[7] == walls.size(),
                  ExcMessage("The DEM checkpoint was written with " +
                             std::to_string(header.size() == 8 ? header[7] : -1) +
                             " walls; this scene has " +
                             std::to_string(walls.size()) +
                             ": restart with the parameters of the run."));
      const std::vector<double> wall_state = read_doubles(in);
      for (unsigned int k = 0; k < walls.size(); ++k)
        {
          const double *w_k = &wall_state[10 * k];
          for (unsigned int d = 0; d < 3; ++d)
            {
              walls[k].point[d]    = w_k[d];
              walls[k].velocity[d] = w_k[3 + d];
              walls[k].force[d]    = w_k[6 + d];
            }
          walls[k].error_integral = w_k[9];
        }

      const std::vector<double> grains_all = read_doubles(in);
      const unsigned int        n_grains   = grains_all.size() / grain_record;
      std::vector<Point<3>>              centers(n_grains);
      std::vector<types::particle_index> ids(n_grains);
      std::vector<std::vector<double>>   properties(n_grains);
      for (unsigned int g = 0; g < n_grains; ++g)
        {
          const double *r = &grains_all[g * grain_record];
          ids[g]          = static_cast<types::particle_index>(r[0]);
          centers[g]      = Point<3>(r[1], r[2], r[3]);
          properties[g].assign(r + 4, r + grain_record);
        }
      insert_local(centers, ids, properties);
      particle_handler.update_cached_numbers();
      AssertThrow(particle_handler.n_global_particles() == n_grains,
                  ExcMessage("The DEM checkpoint holds grains outside this "
                             "scene's domain: restart with the parameters of "
                             "the run."));

      const auto read_histories =
        [&](std::unordered_map<std::uint64_t, ContactHistory> &target) {
          const std::vector<double> list = read_doubles(in);
          for (unsigned int k = 0; k + history_record <= list.size();
               k += history_record)
            {
              ContactHistory h;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  h.shear[d]          = list[k + 2 + d];
                  h.rolling_torque[d] = list[k + 5 + d];
                }
              h.damping_potential = list[k + 8];
              h.damping_force     = list[k + 9];
              target[pair_key(static_cast<types::particle_index>(list[k]),
                              static_cast<types::particle_index>(list[k + 1]))] = h;
            }
        };
      read_histories(restored_pairs);
      read_histories(restored_wall_contacts);

      set_up_time_step();
      current_time   = header[0];
      dt             = header[1];
      n_steps        = static_cast<unsigned long>(header[2]);
      n_builds       = static_cast<unsigned long>(header[3]);
      lost_grains    = static_cast<unsigned int>(header[4]);
      stiffness_rate = header[5];
      damping_rate   = header[6];
      // The lists and histories; the forces of the last step come with the
      // grains (evaluating the contacts again would advance the tangential
      // springs twice).
      rebuild_neighbor_lists();
      // The build counts as the saved run's, which did not rebuild here.
      --n_builds;
    }


    void
    make_contact_mesh(parallel::distributed::Triangulation<3> &tria,
                      const BoundingBox<3>                    &domain,
                      const double                             min_cell_size)
    {
      std::vector<unsigned int> cells(3);
      for (unsigned int d = 0; d < 3; ++d)
        cells[d] = std::clamp(static_cast<unsigned int>(
                                domain.side_length(d) /
                                std::max(min_cell_size, 1e-300)),
                              1u,
                              64u);
      const auto corners = domain.get_boundary_points();
      GridGenerator::subdivided_hyper_rectangle(
        tria, cells, corners.first, corners.second, true);
    }
  } // namespace dem
} // namespace softsand
