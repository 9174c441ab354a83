// The coupled CFD-DEM loop (DESIGN.md section 1): grains of the DEM seen by
// the penalized fluid, fluid forces held over the DEM sub-steps, the fluid
// mesh following the grains.

#include <deal.II/grid/grid_generator.h>

#include <softsand/core/parameter_tools.h>
#include <softsand/core/simulator.h>
#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/dem/pack_generators.h>
#include <softsand/io/grain_file.h>
#include <softsand/io/grain_output.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace core
  {
    template <int dim>
    void
    Simulator<dim>::update_grains_from_dem()
    {
      if constexpr (dim == 3)
        grains = dem->gather_grains(&grain_ids);
      solid_field =
        std::make_unique<coupling::GrainSolidField<dim>>(grains,
                                                         parameters.void_fraction);
      if (fluid)
        fluid->set_solid_field(grains.empty() ? nullptr : solid_field.get());
    }


    template <int dim>
    double
    Simulator<dim>::max_displacement_since_adaptation() const
    {
      // Grains that left the domain change the list: adapt anew.
      if (centers_at_adaptation.size() != grains.size())
        return std::numeric_limits<double>::max();
      double largest = 0;
      for (unsigned int g = 0; g < grains.size(); ++g)
        largest =
          std::max(largest, grains[g].center.distance(centers_at_adaptation[g]));
      return largest;
    }


    template <int dim>
    unsigned int
    Simulator<dim>::adapt_mesh_to_grains(const bool transfer)
    {
      TimerOutput::Scope t(timer, "mesh: follow grains");
      const auto        &m = parameters.mesh;
      unsigned int       sweeps = 0;
      if (!grains.empty() && m.cells_per_diameter > 0)
        {
          const double target =
            solid_field->locator().min_diameter() / m.cells_per_diameter;
          const double margin = parameters.coupling.readapt_fraction * target;
          // One sweep moves cells by one level; grains that moved less than
          // the margin need one. Bounded in case p4est's smoothing undoes
          // a flag each time.
          for (; sweeps < 2 * m.max_refinement_level + 2; ++sweeps)
            {
              if (!coupling::flag_cells_around_grains(triangulation,
                                                      solid_field->locator(),
                                                      target,
                                                      margin,
                                                      m.global_refinements,
                                                      m.max_refinement_level))
                break;
              if (transfer)
                fluid->prepare_for_coarsening_and_refinement();
              triangulation.execute_coarsening_and_refinement();
              if (transfer)
                fluid->transfer_after_coarsening_and_refinement();
            }
        }
      centers_at_adaptation.resize(grains.size());
      for (unsigned int g = 0; g < grains.size(); ++g)
        centers_at_adaptation[g] = grains[g].center;
      return sweeps;
    }


    template <int dim>
    void
    Simulator<dim>::run_coupled()
    {
      if constexpr (dim != 3)
        throw_invalid_parameter("simulation control/mode",
                                "coupled",
                                "coupled (CFD-DEM) scenes are 3D (set "
                                "dimension = 3): the DEM is 3D");
      else
        {
          const auto &p   = parameters;
          const auto &cp  = p.coupling;
          const auto &sc  = p.simulation_control;
          const double rho_f = p.fluid.density;
          const BoundingBox<3> domain(
            std::make_pair(p.mesh.lower_corner, p.mesh.upper_corner));

          // Weights for the fluid mesh partition: a cell cut by a grain
          // surface costs more to assemble (grains at its quadrature
          // points) than a plain cell.
          triangulation.signals.weight.connect(
            [this](const typename Triangulation<dim>::cell_iterator &cell,
                   const typename Triangulation<dim>::CellStatus)
              -> unsigned int {
              if (!solid_field)
                return 1;
              int grain = -1;
              return solid_field->locator().classify_box(cell->bounding_box(),
                                                         grain) ==
                         coupling::GrainLocator<dim>::BoxRelation::cut ?
                       static_cast<unsigned int>(
                         std::round(1 + parameters.coupling.cut_cell_weight)) :
                       1u;
            });

          // The DEM: grains of the scene on a coarse mesh of the same box.
          {
            TimerOutput::Scope t(timer, "grains");
            const std::vector<dem::Grain<3>> initial =
              dem::create_grains(p.grains, domain);
            double r_max = 0;
            for (const auto &g : initial)
              r_max = std::max(r_max, g.radius);
            dem_triangulation =
              std::make_unique<parallel::distributed::Triangulation<3>>(
                mpi_communicator);
            dem::make_contact_mesh(*dem_triangulation,
                                   domain,
                                   2 * r_max * (1 + 0.5 * p.dem.skin_fraction));
            dem = std::make_unique<dem::GranularDynamics>(*dem_triangulation,
                                                          p.dem,
                                                          domain);
            // A restart reads the grains from the checkpoint instead; the
            // scene's grains still fix the coarse mesh, as in the first run.
            if (!sc.restart)
              {
                dem->insert(initial, true);
                dem->initialize();
              }
            else
              grains = initial;
          }
          if (!sc.restart)
            update_grains_from_dem();
          else
            solid_field = std::make_unique<coupling::GrainSolidField<dim>>(
              grains, p.void_fraction);

          fluid = std::make_unique<fluid::PenalizedNavierStokes<dim>>(
            triangulation,
            p.fluid,
            p.fluid_solver,
            p.boundary_conditions,
            progress,
            timer);
          fluid->set_moving_solids(true);

          unsigned int step = 0;
          double       time = 0;
          if (sc.restart)
            std::tie(step, time) = read_checkpoint();
          else
            {
              make_mesh();
              fluid->set_solid_field(grains.empty() ? nullptr :
                                                      solid_field.get());
              fluid->setup_dofs();
              fluid->set_time(0);
              fluid->start_time_stepping();
            }

          progress << "softsand coupled: "
                   << Utilities::MPI::n_mpi_processes(mpi_communicator)
                   << " MPI rank(s), " << grains.size() << " grain(s), "
                   << triangulation.n_global_active_cells() << " cells, "
                   << fluid->n_dofs() << " DoFs, fluid "
                   << (cp.fluid_model ==
                           coupling::CouplingParameters::FluidModel::transient ?
                         "transient" :
                         "quasi-steady")
                   << ", DEM step " << dem->time_step() << " s" << std::endl;

          statistics = std::make_unique<io::StatisticsFile>(
            p.output.directory + "/statistics.txt",
            mpi_communicator,
            sc.restart ? step : io::StatisticsFile::new_file);
          std::unique_ptr<io::GrainOutput> grain_output;
          if (p.output.write_vtu)
            {
              field_output =
                std::make_unique<io::FieldOutput<dim>>(p.output.directory,
                                                       "solution");
              grain_output =
                std::make_unique<io::GrainOutput>(p.output.directory, "grains");
            }

          const bool quasi_steady =
            cp.fluid_model ==
            coupling::CouplingParameters::FluidModel::quasi_steady;
          const bool rigid_nodes =
            p.fluid.solid_model == fluid::FluidParameters::SolidModel::rigid_nodes;
          const double finest = coupling::min_cell_edge(triangulation);
          // Quasi-steady: the held drag must not outlast the grains'
          // response time tau = (rho_s + rho_f / 2) d^2 / (18 mu) (explicit
          // coupling of a linear drag is stable for steps below 2 tau).
          double response_time = std::numeric_limits<double>::max();
          for (const auto &g : grains)
            response_time = std::min(
              response_time,
              (p.dem.material.density + 0.5 * rho_f) * g.diameter() *
                g.diameter() / (18 * p.fluid.viscosity));

          auto &previous_velocity = resistance_history.velocity;
          auto &previous_force    = resistance_history.force;
          auto &previous_angular_velocity =
            resistance_history.angular_velocity;
          auto &previous_torque     = resistance_history.torque;
          auto &previous_resistance = resistance_history.resistance;
          auto &previous_rotational_resistance =
            resistance_history.rotational_resistance;
          Timer        loop_clock;
          while (time < sc.end_time * (1 - 1e-12) && step < sc.max_time_steps)
            {
              ++step;
              // The coupling step.
              double dt = sc.time_step;
              if (quasi_steady)
                {
                  double max_speed = 0;
                  for (const auto &g : grains)
                    max_speed = std::max(max_speed, g.velocity.norm());
                  if (max_speed > 0)
                    dt = std::min(dt,
                                  cp.max_displacement_fraction * finest /
                                    max_speed);
                  dt = std::min(dt, response_time);
                }
              dt = std::min(dt, sc.end_time - time);

              // The mesh follows the grains.
              if (max_displacement_since_adaptation() >
                  cp.readapt_fraction * finest * (1 - 1e-12))
                {
                  adapt_mesh_to_grains(true);
                  ++n_mesh_adaptations;
                }

              // Fluid, with the grains where they are now.
              if (quasi_steady)
                {
                  fluid->set_time(time + dt);
                  fluid->solve_steady_stokes(sc.time_step);
                }
              else
                {
                  fluid->set_time(time + dt);
                  fluid->advance(dt, sc.bdf_order);
                }

              const bool last = time + dt >= sc.end_time * (1 - 1e-12) ||
                                step == sc.max_time_steps;
              const bool write =
                last || (p.output.output_interval > 0 &&
                         step % p.output.output_interval == 0);
              postprocess(step, time + dt, write, false);

              // Fluid force and torque per grain id, held over the DEM
              // sub-steps; the fluid was solved without its hydrostatic
              // pressure, so buoyancy is added here.
              {
                TimerOutput::Scope t(timer, "coupling: forces to grains");
                const auto &forces =
                  cp.paper_force ? grain_forces_eq7 : grain_forces;
                types::particle_index n_ids = 0;
                for (const auto i : grain_ids)
                  n_ids = std::max<types::particle_index>(n_ids, i + 1);
                std::vector<Tensor<1, 3>> force(n_ids), torque(n_ids);
                std::vector<double>       response(n_ids), rotational(n_ids);
                const double              mu = p.fluid.viscosity;
                // Transient model: each grain's clearance, the gap from its
                // surface to the box or the nearest other grain, searched
                // up to a diameter or a finest cell (beyond, it does not
                // matter).
                std::vector<double> clearance;
                if (!quasi_steady)
                  {
                    clearance.resize(grains.size());
                    std::vector<unsigned int> near;
                    for (unsigned int g = 0; g < grains.size(); ++g)
                      {
                        const auto  &c   = grains[g].center;
                        const double r   = grains[g].radius;
                        const double cap = std::max(2 * r, finest);
                        double      &gap = clearance[g];
                        gap              = cap;
                        // Faces with an imposed velocity only, as for the
                        // fluid's free contact cells: a pressure face holds
                        // no layer of fluid against the grain.
                        const auto &bc = p.boundary_conditions;
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            if (bc.imposes_velocity(2 * d))
                              gap = std::min(gap, c[d] - r - p.mesh.lower_corner[d]);
                            if (bc.imposes_velocity(2 * d + 1))
                              gap = std::min(gap, p.mesh.upper_corner[d] - c[d] - r);
                          }
                        BoundingBox<dim> box({c, c});
                        box.extend(r + cap);
                        solid_field->locator().grains_near_box(box, near);
                        for (const unsigned int k : near)
                          if (k != g)
                            gap = std::min(gap,
                                           c.distance(grains[k].center) - r -
                                             grains[k].radius);
                      }
                  }
                for (unsigned int g = 0; g < grains.size(); ++g)
                  {
                    const auto   i = grain_ids[g];
                    const double d = grains[g].diameter();
                    force[i]       = forces.force[g];
                    torque[i]      = forces.torque[g];
                    if (cp.buoyancy)
                      force[i] -= rho_f * grains[g].measure() * p.dem.gravity;
                    // Steady Stokes drag; transient fluid: plus the fluid
                    // that a change of the grain's velocity must set in
                    // motion within the step, the added mass and a shell
                    // one viscous diffusion length sqrt(pi nu dt) thick, or
                    // one cell where the mesh does not resolve that length.
                    response[i] = 3 * M_PI * mu * d;
                    rotational[i] = M_PI * mu * d * d * d;
                    if (!quasi_steady)
                      {
                        const double shell = std::max(
                          finest, std::sqrt(M_PI * mu / rho_f * dt));
                        const double shell_mass = rho_f * M_PI * d * d * shell;
                        // Rigid nodes: the reaction also carries the
                        // inertia of the fluid nodes inside the grain,
                        // which follow it: one displaced mass more.
                        const double covered =
                          cp.added_mass_coefficient +
                          (rigid_nodes ? 1. : 0.);
                        response[i] +=
                          (rho_f * covered * grains[g].measure() +
                           shell_mass) /
                          dt;
                        // The shell turns with the grain: its moment of
                        // inertia (2/3) m r^2.
                        rotational[i] +=
                          shell_mass * d * d / 6 / dt;
                      }
                    // The secants of the last two solves measure the
                    // grain's resistance to translation and rotation:
                    // crowding, walls and the thin fluid layers of contacts
                    // raise it far above the estimates above (a grain on the
                    // floor: 4.5x in the transient model, and a held force
                    // then overshoots, doubling the jitter each step).
                    // Stokes flow is linear in the grain velocities, the
                    // transient response nearly so over a step. In the
                    // transient model a grain within a diameter of a wall
                    // or another grain takes the secant where it is more
                    // than twice the estimate (grains crowding in a closed
                    // box: their held forces swung 1.4x per step
                    // otherwise). A free grain keeps the estimate: its
                    // force also follows its acceleration (added mass,
                    // history), so the secant overstates the resistance
                    // (a free sphere then reached 0.82 U instead of 0.94 U
                    // at 0.05 s), and near its steady velocity the secant of
                    // ever smaller changes amplifies round-off.
                    if (i < previous_velocity.size() &&
                        previous_resistance[i] > 0)
                      {
                        // Within a finest cell: the thin fluid layer there
                        // resists far more than the estimates above. Within
                        // a diameter: neighbours and walls may.
                        const bool always =
                          quasi_steady || clearance[g] < finest;
                        const bool if_larger =
                          !quasi_steady && clearance[g] < 2 * grains[g].radius;
                        const auto secant = [always, if_larger](
                                              const Tensor<1, 3> &dv,
                                                     const Tensor<1, 3> &dF,
                                                     const Tensor<1, 3> &v,
                                                     const double        old,
                                                     const double        low) {
                          double k = old;
                          if (dv.norm() > 1e-2 * v.norm() && dv.norm() > 0 &&
                              dF * dv < 0)
                            k = -(dF * dv) / dv.norm_square();
                          k = std::clamp(k, low, 1e4 * low);
                          return (always || (if_larger && k > 2 * low)) ? k :
                                                                          low;
                        };
                        response[i] =
                          secant(grains[g].velocity - previous_velocity[i],
                                 forces.force[g] - previous_force[i],
                                 grains[g].velocity,
                                 previous_resistance[i],
                                 response[i]);
                        rotational[i] = secant(
                          grains[g].angular_velocity -
                            previous_angular_velocity[i],
                          forces.torque[g] - previous_torque[i],
                          grains[g].angular_velocity,
                          previous_rotational_resistance[i],
                          rotational[i]);
                      }
                    if (previous_velocity.size() < n_ids)
                      {
                        previous_velocity.resize(n_ids);
                        previous_force.resize(n_ids);
                        previous_angular_velocity.resize(n_ids);
                        previous_torque.resize(n_ids);
                        previous_resistance.resize(n_ids, 0.);
                        previous_rotational_resistance.resize(n_ids, 0.);
                      }
                    previous_velocity[i]         = grains[g].velocity;
                    previous_force[i]            = forces.force[g];
                    previous_angular_velocity[i] = grains[g].angular_velocity;
                    previous_torque[i]           = forces.torque[g];
                    previous_resistance[i]       = response[i];
                    previous_rotational_resistance[i] = rotational[i];
                  }
                dem->set_fluid_forces(force, torque, response, rotational);
              }

              {
                TimerOutput::Scope t(timer, "dem: sub-steps");
                const unsigned long steps_before = dem->step_number();
                if (cp.dem_substeps > 0)
                  {
                    const double h = dt / cp.dem_substeps;
                    AssertThrow(h <= dem->time_step() * (1 + 1e-9),
                                ExcMessage(
                                  "coupling/dem substeps = " +
                                  std::to_string(cp.dem_substeps) +
                                  " gives DEM steps of " +
                                  Utilities::to_string(h) +
                                  " s, above the stable DEM step " +
                                  Utilities::to_string(dem->time_step()) +
                                  " s: raise it to at least " +
                                  std::to_string(static_cast<unsigned int>(
                                    std::ceil(dt / dem->time_step()))) +
                                  " or set it to 0 (automatic)."));
                    for (unsigned int k = 0; k < cp.dem_substeps; ++k)
                      dem->step(h);
                  }
                else
                  dem->advance_to(time + dt);
                statistics->add_value("dem_substeps",
                                      dem->step_number() - steps_before);
              }
              time += dt;
              update_grains_from_dem();

              // The grains' side of the statistics row.
              const dem::GranularStatistics s = dem->statistics(domain);
              // A diverged exchange (fluid forces growing step by step)
              // ends here, before a row of NaN is written.
              AssertThrow(std::isfinite(s.kinetic_energy) &&
                            std::isfinite(s.max_speed),
                          ExcMessage(
                            "The coupled run diverged at t = " +
                            Utilities::to_string(time) +
                            " s: the grains' kinetic energy is not finite "
                            "(the fluid force on the grains grew without "
                            "bound). Lower 'simulation control/time step' or "
                            "use 'coupling/fluid model = quasi-steady' with "
                            "'fluid/solid model = rigid nodes'."));
              statistics->add_value("coupling_time_step", dt);
              statistics->add_value("grains", s.n_grains);
              statistics->add_value("kinetic_energy", s.kinetic_energy);
              statistics->add_value("mean_speed", s.mean_speed);
              statistics->add_value("max_speed", s.max_speed);
              statistics->add_value("max_overlap_ratio", s.max_overlap);
              statistics->add_value("coordination", s.coordination);
              statistics->add_value("mesh_adaptations", n_mesh_adaptations);
              statistics->add_value("lost_grains",
                                    Utilities::MPI::sum(dem->n_lost_grains(),
                                                        mpi_communicator));
              // The first grain's state (zero once every grain has left
              // the domain: the columns stay).
              {
                const dem::Grain<dim> first =
                  grains.empty() ? dem::Grain<dim>() : grains[0];
                  const char names[3] = {'x', 'y', 'z'};
                  for (unsigned int d = 0; d < 3; ++d)
                    {
                      statistics->add_value(std::string("grain0_") + names[d],
                                            first.center[d]);
                      statistics->add_value(std::string("grain0_v") + names[d],
                                            first.velocity[d]);
                      statistics->add_value(std::string("grain0_w") + names[d],
                                            first.angular_velocity[d]);
                    }
                }
              for (const auto &wall : dem->get_walls())
                if (wall.shape == dem::Wall::Shape::plane)
                  statistics->add_value(wall.name + "_pressure",
                                        wall.pressure());
              statistics->write_row();

              if (write && grain_output)
                grain_output->write(dem->particles(), time, mpi_communicator);
              if (sc.checkpoint_interval > 0 &&
                  step % sc.checkpoint_interval == 0)
                write_checkpoint(step, time);
              if (step % 10 == 0 || last)
                progress << "   step " << step << ", t = " << time << " s, "
                         << triangulation.n_global_active_cells()
                         << " cells, " << fluid->get_statistics().linear_iterations
                         << " FGMRES iterations, grain 0 at "
                         << (grains.empty() ? Point<dim>() : grains[0].center)
                         << ", " << loop_clock.wall_time() / step
                         << " s per step" << std::endl;
            }

          if (!p.dem.save_pack.empty())
            {
              const auto final_grains = dem->gather_grains();
              if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
                io::write_grain_file<3>(p.output.directory + "/" +
                                          p.dem.save_pack,
                                        final_grains);
            }
          last_results["coupled_steps"]    = step;
          last_results["mesh_adaptations"] = n_mesh_adaptations;
          if (!grains.empty())
            for (unsigned int d = 0; d < 3; ++d)
              {
                last_results["grain0_velocity_" + std::to_string(d)] =
                  grains[0].velocity[d];
                last_results["grain0_center_" + std::to_string(d)] =
                  grains[0].center[d];
              }
          print_results();
          if (p.output.verbosity != io::OutputParameters::Verbosity::quiet)
            timer.print_wall_time_statistics(mpi_communicator);
        }
    }


    template <int dim>
    void
    Simulator<dim>::write_checkpoint(const unsigned int step, const double time)
    {
      if constexpr (dim == 3)
        {
          TimerOutput::Scope t(timer, "checkpoint");
          const std::string base = parameters.output.directory + "/checkpoint";
          // Write to temporary names, then rename: a run stopped while
          // writing leaves the previous checkpoint intact.
          fluid->prepare_for_serialization();
          triangulation.save(base + ".fluid.tmp");
          {
            std::ostringstream dem_state;
            dem->save_state(dem_state);
            if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              {
                std::ofstream out(base + ".dem.tmp", std::ios::binary);
                out << dem_state.str();
                std::ofstream info(base + ".info.tmp");
                info << std::setprecision(17) << step << ' ' << time << ' '
                     << fluid->n_steps_done() << ' ' << n_mesh_adaptations
                     << ' ' << centers_at_adaptation.size() << '\n';
                // Where the mesh was last adapted: the restarted run must
                // re-adapt when the uninterrupted one would.
                for (const auto &c : centers_at_adaptation)
                  info << c << '\n';
                // The measured resistances: the restarted run must
                // linearize the held forces as the uninterrupted one.
                const auto &h = resistance_history;
                info << h.resistance.size() << '\n';
                for (unsigned int i = 0; i < h.resistance.size(); ++i)
                  info << h.velocity[i] << ' ' << h.force[i] << ' '
                       << h.angular_velocity[i] << ' ' << h.torque[i] << ' '
                       << h.resistance[i] << ' ' << h.rotational_resistance[i]
                       << '\n';
              }
          }
          MPI_Barrier(mpi_communicator);
          if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
            {
              namespace fs = std::filesystem;
              const fs::path dir(parameters.output.directory);
              // The info file last: it marks the checkpoint complete.
              for (const auto &entry : fs::directory_iterator(dir))
                {
                  const std::string name = entry.path().filename().string();
                  if (name.rfind("checkpoint.", 0) == 0 &&
                      name.find(".tmp") != std::string::npos &&
                      name != "checkpoint.info.tmp")
                    {
                      std::string final_name = name;
                      final_name.erase(final_name.find(".tmp"), 4);
                      fs::rename(entry.path(), dir / final_name);
                    }
                }
              fs::rename(dir / "checkpoint.info.tmp", dir / "checkpoint.info");
            }
          MPI_Barrier(mpi_communicator);
        }
    }


    template <int dim>
    std::pair<unsigned int, double>
    Simulator<dim>::read_checkpoint()
    {
      if constexpr (dim != 3)
        return {0, 0.};
      else
        {
          TimerOutput::Scope t(timer, "checkpoint");
          const std::string base = parameters.output.directory + "/checkpoint";
          std::ifstream     info(base + ".info");
          AssertThrow(info.good(),
                      ExcMessage("simulation control/restart = true, but there "
                                 "is no checkpoint <" + base +
                                 ".info>: run with a checkpoint interval > 0 "
                                 "first."));
          unsigned int step = 0, fluid_steps = 0, n_centers = 0;
          double       time = 0;
          info >> step >> time >> fluid_steps >> n_mesh_adaptations >>
            n_centers;
          std::vector<Point<dim>> centers(n_centers);
          for (auto &c : centers)
            for (unsigned int d = 0; d < dim; ++d)
              info >> c[d];
          unsigned int n_ids = 0;
          info >> n_ids;
          auto &h = resistance_history;
          h.velocity.resize(n_ids);
          h.force.resize(n_ids);
          h.angular_velocity.resize(n_ids);
          h.torque.resize(n_ids);
          h.resistance.resize(n_ids);
          h.rotational_resistance.resize(n_ids);
          for (unsigned int i = 0; i < n_ids && info; ++i)
            {
              for (auto *v :
                   {&h.velocity[i], &h.force[i], &h.angular_velocity[i],
                    &h.torque[i]})
                for (unsigned int d = 0; d < 3; ++d)
                  info >> (*v)[d];
              info >> h.resistance[i] >> h.rotational_resistance[i];
            }
          AssertThrow(!info.fail(),
                      ExcMessage("The checkpoint <" + base +
                                 ".info> is truncated or corrupt."));

          // The coarse mesh as at the start, then the saved refinement.
          make_mesh(false);
          triangulation.load(base + ".fluid");
          fluid->set_solid_field(nullptr);
          fluid->deserialize(fluid_steps);
          fluid->set_time(time);

          std::ifstream in(base + ".dem", std::ios::binary);
          AssertThrow(in.good(),
                      ExcMessage("The checkpoint <" + base +
                                 ".dem> is missing or unreadable."));
          dem->load_state(in);
          update_grains_from_dem();
          centers_at_adaptation = centers;
          return {step, time};
        }
    }

    // The rest of Simulator is instantiated in simulator.cc.
#define SOFTSAND_INSTANTIATE(dim)                                          \
  template void         Simulator<dim>::run_coupled();                      \
  template void         Simulator<dim>::update_grains_from_dem();           \
  template unsigned int Simulator<dim>::adapt_mesh_to_grains(const bool);   \
  template double Simulator<dim>::max_displacement_since_adaptation() const; \
  template void   Simulator<dim>::write_checkpoint(const unsigned int,       \
                                                 const double);            \
  template std::pair<unsigned int, double> Simulator<dim>::read_checkpoint();
    SOFTSAND_INSTANTIATE(2)
    SOFTSAND_INSTANTIATE(3)
#undef SOFTSAND_INSTANTIATE
  } // namespace core
} // namespace softsand
