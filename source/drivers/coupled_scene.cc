#include <softsand/base/stop_request.h>
#include <softsand/base/warnings.h>
#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/drivers/coupled_scene.h>
#include <softsand/io/scene_grains.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      coupling::HeldForceModel::Settings
      held_force_settings(const core::Parameters<3> &p)
      {
        coupling::HeldForceModel::Settings s;
        s.viscosity     = p.fluid.viscosity;
        s.fluid_density = p.fluid.density;
        s.transient     = p.coupling.fluid_model ==
                      coupling::CouplingParameters::FluidModel::transient;
        // Both constraint models count the covered fluid's mass with the
        // grain (its nodes' reactions carry that fluid's inertia).
        s.rigid_nodes =
          p.fluid.solid_model ==
            fluid::FluidParameters::SolidModel::rigid_nodes ||
          p.fluid.solid_model ==
            fluid::FluidParameters::SolidModel::penalization_limit;
        s.added_mass_coefficient = p.coupling.added_mass_coefficient;
        s.buoyancy               = p.coupling.buoyancy;
        s.gravity                = p.dem.gravity;
        s.box                    = scene_box(p.mesh);
        for (unsigned int face = 0; face < 6; ++face)
          s.face_imposes_velocity[face] =
            p.boundary_conditions.imposes_velocity(face);
        return s;
      }
    } // namespace


    CoupledScene::CoupledScene(const core::Parameters<3> &parameters,
                               const MPI_Comm             comm)
      : parameters(parameters)
      , mpi_communicator(comm)
      , console(parameters.output, comm, parameters.simulation_control.restart)
      , timer(comm, console.progress, TimerOutput::never, TimerOutput::wall_times)
      , box(scene_box(parameters.mesh))
      , fluid(parameters, comm, console.progress, timer)
      , held_force(std::make_unique<coupling::HeldForceModel>(
          held_force_settings(parameters)))
      , grain_columns(probe_box(parameters.dem, box))
    {}


    void
    CoupledScene::run()
    {
      set_up();
      const auto &sc = parameters.simulation_control;
      Timer       loop_clock;
      // Where this process started (a checkpoint's step after a restart):
      // the progress line's rates count this process's steps only.
      first_step = step;
      start_time = time;
      while (!sc.reached_end(time, step) && developed_fracture.empty())
        {
          ++step;
          const double dt = choose_time_step();
          follow_grains();
          judge_fracture_development();
          solve_fluid(dt);
          const bool last =
            sc.reached_end(time + dt, step) || !developed_fracture.empty();
          const bool write = parameters.output.output_due(step, last);
          record_fluid(time + dt, write);
          hand_forces_to_grains(dt);
          advance_grains(dt);
          time += dt;
          update_grains_from_dem();
          record_grains(dt);
          if (write && grain_output)
            grain_output->write(dem->particles(), time, step, mpi_communicator);
          const bool checkpointed =
            sc.checkpoint_interval > 0 && step % sc.checkpoint_interval == 0;
          if (checkpointed)
            write_checkpoint();
          report_progress(last, loop_clock);
          if (stop_on_request(checkpointed))
            break;
        }
      finish();
    }


    void
    CoupledScene::set_up()
    {
      const auto &p  = parameters;
      const auto &sc = p.simulation_control;
      make_output_directory(p.output.directory, mpi_communicator);
      fluid.weight_cut_cells(p.coupling.cut_cell_weight);

      // The DEM: grains of the scene on a coarse mesh of the same box.
      {
        TimerOutput::Scope t(timer, "grains");
        const std::vector<dem::Grain<3>> initial =
          io::create_scene_grains(p.grains, box);
        dem_triangulation =
          std::make_unique<parallel::distributed::Triangulation<3>>(
            mpi_communicator);
        dem::make_contact_mesh(*dem_triangulation,
                               box,
                               contact_mesh_cell_size(initial,
                                                      p.dem.skin_fraction));
        dem = std::make_unique<dem::GranularDynamics>(*dem_triangulation,
                                                      p.dem,
                                                      box);
        // A restart reads the grains from the checkpoint instead; the
        // scene's grains still fix the coarse mesh, as in the first run.
        if (!sc.restart)
          {
            dem::check_wall_overlaps(initial,
                                     dem->get_walls(),
                                     p.grains.max_overlap_ratio);
            dem->insert(initial, true);
            dem->initialize();
          }
        else
          fluid.set_grains(initial);
      }
      if (!sc.restart)
        update_grains_from_dem();
      fluid.create_solver(true);
      // Before the checkpoint is read: it holds the stall window.
      if (p.fracture_area.enabled && p.fracture_area.stops_set())
        fracture_development =
          std::make_unique<postprocess::FractureDevelopment>(
            p.fracture_area,
            p.boundary_conditions.inlet_region(),
            p.mesh.lower_corner,
            p.mesh.upper_corner,
            mpi_communicator);

      if (sc.restart)
        read_checkpoint();
      else
        {
          fluid.make_mesh(true, true);
          fluid.solver().setup_dofs();
          fluid.solver().set_time(0);
          fluid.solver().start_time_stepping();
        }

      console.progress
        << "softsand coupled: "
        << Utilities::MPI::n_mpi_processes(mpi_communicator) << " MPI rank(s), "
        << fluid.grains().size() << " grain(s), "
        << fluid.triangulation().n_global_active_cells() << " cells, "
        << fluid.solver().n_dofs() << " DoFs, fluid "
        << (p.coupling.fluid_model ==
                coupling::CouplingParameters::FluidModel::transient ?
              "transient" :
              "quasi-steady")
        << ", DEM step " << dem->time_step() << " s" << std::endl;

      statistics = std::make_unique<io::StatisticsFile>(
        p.output.directory + "/statistics.txt",
        mpi_communicator,
        sc.restart ? long(step) : io::StatisticsFile::new_file);
      if (p.output.write_vtu)
        grain_output =
          std::make_unique<io::GrainOutput>(p.output.directory, "grains");
      if (sc.restart)
        {
          // Output numbering and series continue: nothing of the first run
          // is overwritten.
          fluid.resume_field_output(time);
          if (grain_output)
            grain_output->resume(time);
          console.pcout << "softsand coupled: resumed at step " << step
                        << ", t = " << time << " s, from the checkpoint in "
                        << p.output.directory << std::endl;
        }
      else if (p.output.write_vtu)
        {
          // Step 0: the state the run starts from, in every series.
          fluid.write_initial_state(time);
          grain_output->write(dem->particles(), time, 0, mpi_communicator);
        }

      finest_cell = coupling::min_cell_edge(fluid.triangulation());
      // Quasi-steady: the held drag must not outlast the grains' response
      // time tau = (rho_s + rho_f / 2) d^2 / (18 mu) (explicit coupling of
      // a linear drag is stable for steps below 2 tau).
      response_time = std::numeric_limits<double>::max();
      for (const auto &g : fluid.grains())
        response_time =
          std::min(response_time,
                   (p.dem.material.density + 0.5 * p.fluid.density) *
                     g.diameter() * g.diameter() / (18 * p.fluid.viscosity));
      warn_about_fluid_model(p, !fluid.grains().empty(), mpi_communicator);
      warn_about_response_time();
      warn_about_penalty_coupling();
    }


    void
    CoupledScene::warn_about_response_time() const
    {
      const double dt = parameters.simulation_control.time_step;
      if (fluid.grains().empty() || !(dt > response_time))
        return;
      std::ostringstream text;
      text << std::setprecision(3) << "simulation control/time step = " << dt
           << " s is " << dt / response_time
           << " times the response time (rho_s + rho_f / 2) d^2 / (18 mu) = "
           << response_time << " s of the smallest grain";
      if (parameters.coupling.fluid_model ==
          coupling::CouplingParameters::FluidModel::quasi_steady)
        text << ": the quasi-steady coupling steps are limited to it.";
      else
        text << ": the fluid force held over a step lags the grains, and "
                "free grains overshoot their terminal velocity (a free "
                "sphere at 5.7 response times ended at 1.5 times the stream "
                "velocity). Lower the time step below the response time.";
      base::warn(text.str(), mpi_communicator);
    }


    void
    CoupledScene::warn_about_penalty_coupling() const
    {
      const auto &p = parameters;
      if (p.fluid.solid_model !=
            fluid::FluidParameters::SolidModel::penalization ||
          fluid.grains().size() < 2)
        return;
      double smallest = std::numeric_limits<double>::max();
      for (const auto &g : fluid.grains())
        smallest = std::min(smallest, g.measure());
      const double n = coupling::penalty_coupling_number(p.fluid.theta,
                                                         p.fluid.density,
                                                         p.dem.material.density,
                                                         finest_cell,
                                                         smallest);
      if (!(n > coupling::max_stable_penalty_coupling))
        return;
      std::ostringstream text;
      text << std::setprecision(3) << "fluid/theta = " << p.fluid.theta
           << " with fluid/solid model = penalization: grains that share a "
              "cell (or touch a wall) are held together by the penalty, "
              "and the penalty coupling number Theta (rho_f / rho_s) h^3 / V "
              "= "
           << n << " (finest cell h = " << finest_cell
           << " m, smallest grain V = " << smallest
           << " m^3) is above " << coupling::max_stable_penalty_coupling
           << ": the coupled step is likely unstable (grains at tens of m/s "
              "within a few steps; on the small Hele-Shaw scene stable at 36, "
              "not at 362, whatever the time step). Lower fluid/theta below "
           << p.fluid.theta * coupling::max_stable_penalty_coupling / n
           << " (the grains then leak: doc/hele_shaw.md), refine the mesh, or "
              "use fluid/solid model = rigid nodes.";
      base::warn(text.str(), mpi_communicator);
    }


    double
    CoupledScene::choose_time_step()
    {
      const auto &sc = parameters.simulation_control;
      double      dt = sc.time_step;
      if (parameters.coupling.fluid_model ==
          coupling::CouplingParameters::FluidModel::quasi_steady)
        {
          double max_speed = 0;
          for (const auto &g : fluid.grains())
            max_speed = std::max(max_speed, g.velocity.norm());
          if (max_speed > 0)
            dt = std::min(dt,
                          parameters.coupling.max_displacement_fraction *
                            finest_cell / max_speed);
          dt = std::min(dt, response_time);
          return std::min(dt, sc.end_time - time);
        }
      // Transient: halvings of the scene's step keep the steps equal (BDF2)
      // over long stretches.
      double rate = 0;
      {
        TimerOutput::Scope t(timer, "fluid: courant number");
        rate = fluid.solver().max_velocity_per_cell_size();
      }
      const double limit = parameters.coupling.max_courant_number;
      // The accuracy limit: the relative change of the velocity per step is
      // proportional to the step, so the last step's gives the rate.
      const double change_limit = parameters.coupling.max_velocity_change;
      const double last         = fluid.solver().last_transient_step();
      const double change_rate =
        (change_limit > 0 && last > 0) ?
          fluid.solver().relative_velocity_change() / last :
          0.;
      const auto too_long = [&](const double step) {
        return (limit > 0 && step * rate > limit) ||
               (change_rate > 0 && step * change_rate > change_limit);
      };
      if (limit > 0 || change_limit > 0)
        {
          for (unsigned int halvings = 0; halvings < 10 && too_long(dt);
               ++halvings)
            dt /= 2;
          // The step grows by doublings, never in two steps running: BDF2
          // on the changed step (ratio 2, mass term 5/3 rho / dt) stays
          // zero-stable, where restarting it with BDF1 (rho / dt) made
          // convection weigh 1.5x more and a 32 kPa injection take 48-389
          // FGMRES iterations after doublings to Courant 1.42-1.48.
          if (last > 0 && dt > last * (1 + 1e-9))
            dt = (fluid.solver().last_step_ratio() > 1 + 1e-9) ?
                   last :
                   std::min(dt, 2 * last);
        }
      dt             = std::min(dt, sc.end_time - time);
      courant_number = dt * rate;
      warn_about_courant_number();
      return dt;
    }


    void
    CoupledScene::warn_about_courant_number() const
    {
      const double limit = parameters.coupling.max_courant_number;
      if (courant_number <= 1.5 || (limit > 0 && courant_number <= limit))
        return;
      std::ostringstream text;
      text << std::setprecision(3) << "the transient fluid step runs at a cell "
           << "Courant number |u| dt / h of " << courant_number << " at t = "
           << time << " s (simulation control/time step = "
           << parameters.simulation_control.time_step
           << " s): the Oseen solve's iterations grow above about 1.5 and "
              "it failed at 2.5 (doc/notes/solver_study.md). Set coupling/max "
              "courant number (e.g. 1.5) to halve the step where the flow "
              "is fast.";
      base::warn_once("coupling courant number", text.str(), mpi_communicator);
    }


    void
    CoupledScene::follow_grains()
    {
      if (fluid.max_displacement_since_adaptation() >
          parameters.coupling.readapt_fraction * finest_cell * (1 - 1e-12))
        {
          fluid.adapt_to_grains(true);
          ++n_mesh_adaptations;
        }
    }


    bool
    CoupledScene::stop_on_request(const bool checkpointed)
    {
      if (!base::stop_requested(mpi_communicator))
        return false;
      if (!checkpointed)
        write_checkpoint();
      std::ostringstream where;
      where << "step " << step << ", t = " << time << " s";
      end_reason = "stopped on request (checkpoint written; restart = true "
                   "continues)";
      base::report_stop(console.pcout, where.str(),
                        parameters.output.directory);
      return true;
    }


    void
    CoupledScene::judge_fracture_development()
    {
      if (!fracture_development)
        return;
      developed_fracture = fracture_development->check(fluid.grains(), time);
      if (!developed_fracture.empty())
        {
          end_reason = "the fracture developed (" + developed_fracture + ")";
          console.pcout << "Developed fracture at step " << step << ", t = "
                        << time << " s: " << developed_fracture
                        << "; the run ends after this step." << std::endl;
        }
    }


    void
    CoupledScene::solve_fluid(const double dt)
    {
      const auto &sc     = parameters.simulation_control;
      auto       &solver = fluid.solver();
      solver.set_time(time + dt);
      if (parameters.coupling.fluid_model ==
          coupling::CouplingParameters::FluidModel::quasi_steady)
        solver.solve_steady_stokes(sc.time_step);
      else
        solver.advance(dt, sc.bdf_order);
    }


    void
    CoupledScene::record_fluid(const double row_time, const bool write_fields)
    {
      postprocess::Columns row = fluid.postprocess(step, row_time, write_fields);
      add_fluid_row(row, step, row_time, wall_clock.wall_time(), *statistics);
      last_results = row;
    }


    void
    CoupledScene::hand_forces_to_grains(const double dt)
    {
      TimerOutput::Scope t(timer, "coupling: forces to grains");
      const auto &forces =
        parameters.coupling.paper_force ? fluid.forces_eq7() : fluid.forces();
      const coupling::HeldForces held =
        held_force->compute(fluid.grains(),
                            grain_ids,
                            forces,
                            fluid.solid_field().locator(),
                            finest_cell,
                            dt);
      dem->set_fluid_forces(held.force,
                            held.torque,
                            held.resistance,
                            held.rotational_resistance);
    }


    void
    CoupledScene::advance_grains(const double dt)
    {
      TimerOutput::Scope  t(timer, "dem: sub-steps");
      const unsigned int  substeps     = parameters.coupling.dem_substeps;
      const unsigned long steps_before = dem->step_number();
      if (substeps > 0)
        {
          const double h = dt / substeps;
          AssertThrow(h <= dem->time_step() * (1 + 1e-9),
                      ExcMessage(
                        "coupling/dem substeps = " + std::to_string(substeps) +
                        " gives DEM steps of " + Utilities::to_string(h) +
                        " s, above the stable DEM step " +
                        Utilities::to_string(dem->time_step()) +
                        " s: raise it to at least " +
                        std::to_string(static_cast<unsigned int>(
                          std::ceil(dt / dem->time_step()))) +
                        " or set it to 0 (automatic)."));
          for (unsigned int k = 0; k < substeps; ++k)
            dem->step(h);
        }
      else
        dem->advance_to(time + dt);
      statistics->add_value("dem_substeps", dem->step_number() - steps_before);
    }


    void
    CoupledScene::update_grains_from_dem()
    {
      fluid.set_grains(dem->gather_grains(&grain_ids));
    }


    void
    CoupledScene::record_grains(const double dt)
    {
      statistics->add_value("coupling_time_step", dt);
      if (courant_number >= 0)
        statistics->add_value("courant_number", courant_number);
      if (parameters.coupling.fluid_model ==
          coupling::CouplingParameters::FluidModel::transient)
        statistics->add_value("velocity_change",
                              fluid.solver().relative_velocity_change());
      const dem::GranularStatistics s =
        grain_columns.add_columns(*dem, *statistics, mpi_communicator);
      // A diverged exchange (fluid forces growing step by step) ends here,
      // before a row of NaN is written.
      AssertThrow(std::isfinite(s.kinetic_energy) && std::isfinite(s.max_speed),
                  ExcMessage(
                    "The coupled run diverged at t = " +
                    Utilities::to_string(time) +
                    " s: the grains' kinetic energy is not finite (the fluid "
                    "force on the grains grew without bound). Lower "
                    "'simulation control/time step' or use 'coupling/fluid "
                    "model = quasi-steady' with 'fluid/solid model = rigid "
                    "nodes'."));
      statistics->add_value("mesh_adaptations", n_mesh_adaptations);
      postprocess::add_first_grain_columns(fluid.grains(), *statistics);
      statistics->write_row();
    }


    void
    CoupledScene::report_progress(const bool last, const Timer &loop_clock)
    {
      // A line per step, but at most one every 5 s on quick steps.
      const double now = loop_clock.wall_time();
      if (!last && now < last_report + 5)
        return;
      last_report = now;
      console.progress
        << "   step " << step << ", t = " << time << " s ("
        << progress_of(time,
                       start_time,
                       parameters.simulation_control.end_time,
                       now)
        << "), " << fluid.triangulation().n_global_active_cells()
        << " cells, " << fluid.solver().get_statistics().linear_iterations
        << " FGMRES iterations, grain 0 at "
        << (fluid.grains().empty() ? Point<3>() : fluid.grains()[0].center)
        << ", " << now / (step - first_step) << " s per step" << std::endl;
    }


    void
    CoupledScene::finish()
    {
      const auto &p = parameters;
      if (!p.dem.save_pack.empty())
        save_pack(*dem, p.output.directory, p.dem.save_pack, mpi_communicator);
      last_results["coupled_steps"]    = step;
      last_results["mesh_adaptations"] = n_mesh_adaptations;
      if (fracture_development)
        last_results["fracture_developed"] = developed_fracture.empty() ? 0 : 1;
      // The first grain's state under the names of its statistics columns.
      if (!fluid.grains().empty())
        for (unsigned int d = 0; d < 3; ++d)
          {
            const std::string axis(1, "xyz"[d]);
            last_results["grain0_v" + axis] = fluid.grains()[0].velocity[d];
            last_results["grain0_" + axis]  = fluid.grains()[0].center[d];
          }
      print_fluid_results(console.pcout, 3, last_results);
      print_run_summary(console.pcout,
                        std::to_string(step - first_step) +
                          " coupled steps in this process (to step " +
                          std::to_string(step) + ")",
                        time,
                        end_reason,
                        last_results,
                        p.output.directory,
                        mpi_communicator);
      // On screen unless quiet, in log.txt always (console.progress).
      timer.print_wall_time_statistics(mpi_communicator);
    }
  } // namespace drivers
} // namespace softsand
