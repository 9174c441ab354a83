#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>

#include <iomanip>
#include <sstream>

#include <softsand/base/stop_request.h>
#include <softsand/drivers/checkpoint_files.h>
#include <softsand/drivers/fluid_scene.h>
#include <softsand/io/scene_grains.h>

namespace softsand
{
  namespace drivers
  {
    template <int dim>
    FluidScene<dim>::FluidScene(const core::Parameters<dim> &parameters,
                                const MPI_Comm               comm)
      : parameters(parameters)
      , mpi_communicator(comm)
      , console(parameters.output, comm, parameters.simulation_control.restart)
      , timer(comm, console.progress, TimerOutput::never, TimerOutput::wall_times)
      , fluid(parameters, comm, console.progress, timer)
    {}


    template <int dim>
    void
    FluidScene<dim>::run()
    {
      const auto &p = parameters;
      make_output_directory(p.output.directory, mpi_communicator);
      {
        TimerOutput::Scope t(timer, "grains");
        fluid.set_grains(
          io::create_scene_grains(p.grains, scene_box(p.mesh)));
      }
      warn_about_fluid_model(p, !fluid.grains().empty(), mpi_communicator);
      const bool restart = p.simulation_control.restart;
      if (restart)
        load_checkpoint_mesh();
      else
        fluid.make_mesh(true, false);
      console.progress << "softsand: " << dim << "D, "
                       << Utilities::MPI::n_mpi_processes(mpi_communicator)
                       << " MPI rank(s), " << fluid.grains().size()
                       << " grain(s), "
                       << fluid.triangulation().n_global_active_cells()
                       << " cells" << std::endl;

      statistics = std::make_unique<io::StatisticsFile>(
        p.output.directory + "/statistics.txt",
        mpi_communicator,
        restart ? long(first_step) : io::StatisticsFile::new_file,
        dim);
      fluid.create_solver(false);

      if (p.simulation_control.is_steady())
        solve_steady();
      else
        march_in_time();

      print_fluid_results(console.pcout, dim, last_results);
      // On screen unless quiet, in log.txt always (console.progress).
      timer.print_wall_time_statistics(mpi_communicator);
    }


    template <int dim>
    void
    FluidScene<dim>::solve_steady()
    {
      const auto &p      = parameters;
      auto       &solver = fluid.solver();
      for (unsigned int cycle = 0; cycle <= p.mesh.kelly_cycles; ++cycle)
        {
          if (cycle > 0)
            refine_by_velocity_error();
          solver.setup_dofs();
          solver.set_time(0);
          console.progress << "   solve " << cycle << ": "
                           << fluid.triangulation().n_global_active_cells()
                           << " cells, " << solver.n_dofs() << " DoFs"
                           << std::endl;
          if (p.simulation_control.mode ==
              core::SimulationControl::Mode::steady_stokes)
            solver.solve_steady_stokes(p.simulation_control.time_step);
          else
            solver.solve_steady_navier_stokes(p.simulation_control.time_step);
          record(cycle, 0., true);
        }
    }


    template <int dim>
    void
    FluidScene<dim>::march_in_time()
    {
      const auto  &sc     = parameters.simulation_control;
      auto        &solver = fluid.solver();
      const double dt     = sc.time_step;
      double       time = first_time;
      unsigned int step = first_step;
      if (sc.restart)
        {
          solver.deserialize(first_steps_done);
          solver.set_time(time);
          // Output numbering and series continue: nothing of the first run
          // is overwritten.
          fluid.resume_field_output(time);
          console.pcout << "softsand: resumed at step " << step << ", t = "
                        << time << " s, from the checkpoint in "
                        << parameters.output.directory << std::endl;
        }
      else
        {
          solver.setup_dofs();
          solver.set_time(0);
          solver.start_time_stepping();
          if (parameters.output.write_vtu)
            fluid.write_initial_state(time);
        }
      Timer        loop_clock;
      double       last_report = -1e300;
      const double start_time  = time;
      while (!sc.reached_end(time, step))
        {
          ++step;
          time += dt;
          solver.set_time(time);
          solver.advance(dt, sc.bdf_order);
          const bool steady =
            sc.steady_state_tolerance > 0 &&
            solver.relative_velocity_change() < sc.steady_state_tolerance;
          const bool last = steady || sc.reached_end(time, step);
          record(step, time, parameters.output.output_due(step, last));
          const bool checkpointed = sc.checkpoint_interval > 0 &&
                                    step % sc.checkpoint_interval == 0 && !last;
          if (checkpointed)
            write_checkpoint(step, time);
          if (!last && base::stop_requested(mpi_communicator))
            {
              if (!checkpointed)
                write_checkpoint(step, time);
              std::ostringstream where;
              where << "step " << step << ", t = " << time << " s";
              base::report_stop(console.pcout, where.str(),
                                parameters.output.directory);
              break;
            }
          // A line per step, but at most one every 5 s on quick steps.
          if (last || loop_clock.wall_time() >= last_report + 5)
            {
              last_report = loop_clock.wall_time();
              console.progress
                << "   step " << step << ", t = " << time << " s ("
                << progress_of(time, start_time, sc.end_time, last_report)
                << "), "
                << solver.get_statistics().linear_iterations
                << " FGMRES iterations, relative change "
                << solver.relative_velocity_change() << std::endl;
            }
          if (steady)
            break;
        }
    }


    template <int dim>
    void
    FluidScene<dim>::write_checkpoint(const unsigned int step,
                                      const double       time)
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string dir = parameters.output.directory;
      fluid.solver().prepare_for_serialization();
      fluid.triangulation().save(checkpoint_base(dir, step) + ".fluid");
      std::ostringstream info;
      info << std::setprecision(17) << step << ' ' << time << ' '
           << fluid.solver().n_steps_done() << '\n';
      commit_checkpoint(dir,
                        step,
                        "transient",
                        scene_fingerprint(parameters),
                        info.str(),
                        mpi_communicator);
    }


    template <int dim>
    void
    FluidScene<dim>::load_checkpoint_mesh()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string  dir  = parameters.output.directory;
      std::istringstream info = read_checkpoint_info(
        dir, "transient", scene_fingerprint(parameters), mpi_communicator);
      info >> first_step >> first_time >> first_steps_done;
      check_checkpoint_info(info, dir);
      // The coarse mesh as at the start, then the saved refinement; the
      // fields are read once the solver exists (march_in_time()).
      fluid.make_mesh(false, false);
      fluid.triangulation().load(checkpoint_base(dir, first_step) + ".fluid");
    }


    template <int dim>
    void
    FluidScene<dim>::refine_by_velocity_error()
    {
      TimerOutput::Scope t(timer, "mesh");
      auto              &tria = fluid.triangulation();
      const auto        &solver = fluid.solver();
      Vector<float>      indicators(tria.n_active_cells());
      const FEValuesExtractors::Vector velocities(0);
      KellyErrorEstimator<dim>::estimate(
        solver.get_dof_handler(),
        QGauss<dim - 1>(3),
        {},
        solver.get_solution(),
        indicators,
        solver.get_fe().component_mask(velocities));
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
        tria, indicators, parameters.mesh.kelly_refine_fraction, 0.);
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->level() >= int(parameters.mesh.max_refinement_level))
          cell->clear_refine_flag();
      tria.execute_coarsening_and_refinement();
    }


    template <int dim>
    void
    FluidScene<dim>::record(const unsigned int step,
                            const double       time,
                            const bool         write_fields)
    {
      postprocess::Columns row = fluid.postprocess(step, time, write_fields);
      add_fluid_row(row, step, time, wall_clock.wall_time(), *statistics);
      statistics->write_row();
      last_results = row;
    }

    template class FluidScene<2>;
    template class FluidScene<3>;
  } // namespace drivers
} // namespace softsand
