#include <softsand/base/stop_request.h>
#include <softsand/base/warnings.h>
#include <softsand/drivers/checkpoint_files.h>
#include <softsand/drivers/granular_scene.h>
#include <softsand/io/grain_file.h>
#include <softsand/io/scene_grains.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    GranularScene::GranularScene(const core::Parameters<3> &parameters,
                                 const MPI_Comm             comm)
      : parameters(parameters)
      , mpi_communicator(comm)
      , console(parameters.output, comm, parameters.simulation_control.restart)
      , box(scene_box(parameters.mesh))
      , grain_columns(probe_box(parameters.dem, box))
      , triangulation(comm)
    {}


    void
    GranularScene::run()
    {
      set_up();
      // A restarted run's row and files of its first step exist already.
      if (!parameters.simulation_control.restart)
        {
          record();
          write_grains();
        }
      loop_clock.restart();
      start_time = dem->time();
      bool               last_recorded = true;
      const unsigned int checkpoint_interval =
        parameters.simulation_control.checkpoint_interval;
      while (!finished())
        {
          dem->step();
          const unsigned long n = dem->step_number();
          last_recorded =
            (n % parameters.dem.statistics_interval == 0) || finished();
          if (last_recorded)
            {
              record();
              settled = check_settled();
            }
          if (parameters.dem.output_interval > 0 &&
              n % parameters.dem.output_interval == 0)
            write_grains();
          const bool checkpointed = checkpoint_interval > 0 &&
                                    n % checkpoint_interval == 0 &&
                                    !settled && !finished();
          if (checkpointed)
            write_checkpoint();
          report_progress();
          if (settled)
            break;
          // Checked at the statistics rows: a collective per DEM step would
          // cost more than the step.
          if (last_recorded && !finished() &&
              base::stop_requested(mpi_communicator))
            {
              if (!checkpointed)
                write_checkpoint();
              base::report_stop(console.pcout,
                                "DEM step " + std::to_string(n),
                                parameters.output.directory);
              break;
            }
        }
      finish(last_recorded);
    }


    void
    GranularScene::write_checkpoint()
    {
      const std::string   dir  = parameters.output.directory;
      const unsigned long step = dem->step_number();
      std::ostringstream  dem_state;
      dem->save_state(dem_state);
      std::ostringstream info;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          std::ofstream out(checkpoint_base(dir, step) + ".dem",
                            std::ios::binary);
          out << dem_state.str();
          info << std::setprecision(17) << step << ' ' << dem->time() << ' '
               << settled_rows << ' ' << max_servo_error << '\n';
        }
      commit_checkpoint(dir,
                        step,
                        "granular",
                        scene_fingerprint(parameters),
                        info.str(),
                        mpi_communicator);
    }


    void
    GranularScene::read_checkpoint()
    {
      const std::string  dir  = parameters.output.directory;
      std::istringstream info = read_checkpoint_info(
        dir, "granular", scene_fingerprint(parameters), mpi_communicator);
      unsigned long      step = 0;
      double             time = 0;
      info >> step >> time >> settled_rows >> max_servo_error;
      check_checkpoint_info(info, dir);
      std::ifstream in = open_checkpoint_file(checkpoint_base(dir, step) + ".dem");
      dem->load_state(in);
      first_step = step;
    }


    void
    GranularScene::set_up()
    {
      const auto &p  = parameters;
      const auto &dp = p.dem;
      make_output_directory(p.output.directory, mpi_communicator);

      const std::vector<dem::Grain<3>> grains =
        io::create_scene_grains(p.grains, box);
      dem::make_contact_mesh(triangulation,
                             box,
                             contact_mesh_cell_size(grains, dp.skin_fraction));
      dem = std::make_unique<dem::GranularDynamics>(triangulation, dp, box);
      const bool restart = p.simulation_control.restart;
      // A restart reads the grains from the checkpoint; the scene's grains
      // still size the contact mesh, as in the first run.
      if (restart)
        read_checkpoint();
      else
        {
          dem::check_wall_overlaps(grains,
                                     dem->get_walls(),
                                     p.grains.max_overlap_ratio);
          dem->insert(grains, true);
          dem->initialize();
        }

      console.progress << "softsand granular: "
                       << Utilities::MPI::n_mpi_processes(mpi_communicator)
                       << " MPI rank(s), " << grains.size() << " grain(s), "
                       << dem->get_walls().size() << " wall(s), dt = "
                       << dem->time_step() << " s = "
                       << (dem->rayleigh_time() > 0 ?
                             dem->time_step() / dem->rayleigh_time() :
                             0.)
                       << " Rayleigh time" << std::endl;

      statistics = std::make_unique<io::StatisticsFile>(
        p.output.directory + "/statistics.txt",
        mpi_communicator,
        restart ? long(first_step) : io::StatisticsFile::new_file);
      if (p.output.write_vtu)
        {
          grain_output =
            std::make_unique<io::GrainOutput>(p.output.directory, "grains");
          if (!dem->get_walls().empty())
            wall_output =
              std::make_unique<io::WallOutput>(p.output.directory, "walls", box);
        }
      if (restart)
        {
          // Output numbering and series continue: nothing of the first run
          // is overwritten.
          if (grain_output)
            grain_output->resume(dem->time());
          if (wall_output)
            wall_output->resume(dem->time());
          console.pcout << "softsand granular: resumed at step " << first_step
                        << ", t = " << dem->time()
                        << " s, from the checkpoint in " << p.output.directory
                        << std::endl;
        }
      if (!restart && !dp.save_initial_pack.empty() &&
          Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        io::write_grain_file<3>(p.output.directory + "/" + dp.save_initial_pack,
                                grains);
    }


    bool
    GranularScene::finished() const
    {
      return dem->time() + 0.5 * dem->time_step() >=
               parameters.simulation_control.end_time ||
             dem->step_number() >= parameters.simulation_control.max_time_steps;
    }


    void
    GranularScene::record()
    {
      statistics->add_value("time", dem->time());
      statistics->add_value("step", dem->step_number());
      last_statistics =
        grain_columns.add_columns(*dem, *statistics, mpi_communicator);
      // Hertz-Mindlin and the simplified JKR cohesion are small-overlap
      // laws: beyond the overlap the scene accepts in a grain file, say so
      // (the paper's soft grains with 1e6 J/m^3 of cohesion reach 2 R*).
      const double limit = parameters.grains.max_overlap_ratio;
      if (last_statistics.max_overlap > limit)
        {
          std::ostringstream message;
          message << std::setprecision(3) << "at t = " << dem->time()
                  << " s two grains overlap by "
                  << last_statistics.max_overlap
                  << " R* (mean over contacts "
                  << last_statistics.mean_overlap
                  << "), more than grains/max overlap ratio = " << limit
                  << ": the contact law (small overlaps) is outside its "
                     "validity, and a grain file of this pack is refused "
                     "at that ratio. "
                     "Grains too soft (dem/material/youngs modulus) for "
                     "this load, or cohesion (dem/material/cohesion energy "
                     "density) pulling them together?";
          base::warn_once("granular overlap", message.str(), mpi_communicator);
        }
      statistics->add_value("wall_time", wall_clock.wall_time());
      statistics->write_row();
    }


    void
    GranularScene::write_grains()
    {
      if (grain_output)
        grain_output->write(dem->particles(),
                            dem->time(),
                            dem->step_number(),
                            mpi_communicator);
      if (wall_output)
        wall_output->write(dem->get_walls(),
                           dem->time(),
                           dem->step_number(),
                           mpi_communicator);
    }


    bool
    GranularScene::check_settled()
    {
      const auto &dp          = parameters.dem;
      const auto &s           = last_statistics;
      double      servo_error = 0;
      for (const auto &wall : dem->get_walls())
        if (wall.motion == dem::Wall::Motion::servo)
          servo_error =
            std::max(servo_error,
                     std::abs(wall.pressure() / wall.target_pressure - 1));
      if (dp.settled_kinetic_energy > 0 && s.n_grains > 0 &&
          s.kinetic_energy / s.n_grains < dp.settled_kinetic_energy &&
          servo_error < dp.walls.servo_tolerance)
        {
          max_servo_error = std::max(max_servo_error, servo_error);
          return ++settled_rows >= dp.settled_checks;
        }
      settled_rows    = 0;
      max_servo_error = 0;
      return false;
    }


    void
    GranularScene::report_progress()
    {
      if (wall_clock.wall_time() <= next_report)
        return;
      console.progress << "  t = " << dem->time() << " s ("
                       << progress_of(dem->time(),
                                      start_time,
                                      parameters.simulation_control.end_time,
                                      loop_clock.wall_time())
                       << "), step " << dem->step_number() << ", dt "
                       << dem->time_step()
                       << " s, kinetic energy "
                       << last_statistics.kinetic_energy << " J, "
                       << std::setprecision(3)
                       << (dem->step_number() - first_step) *
                            last_statistics.n_grains / wall_clock.wall_time()
                       << " grain-steps/s" << std::setprecision(6)
                       << std::endl;
      next_report += 10;
    }


    std::string
    GranularScene::unsettled_note() const
    {
      const auto        &dp = parameters.dem;
      const auto        &s  = last_statistics;
      std::ostringstream note;
      note << std::setprecision(3) << "unsettled: saved at t = " << dem->time()
           << " s with kinetic energy " << s.kinetic_energy / std::max(1u, s.n_grains)
           << " J per grain and a fastest grain at " << s.max_speed << " m/s";
      if (dp.settled_kinetic_energy > 0)
        {
          note << ", above dem/settled kinetic energy = "
               << dp.settled_kinetic_energy << " J";
          base::warn("dem/save pack = " + dp.save_pack + ": the pack is " +
                       note.str() +
                       " (the run reached its end before settling; raise "
                       "simulation control/end time). Its file says so.",
                     mpi_communicator);
        }
      else
        note << " (settling not checked: dem/settled kinetic energy = 0)";
      return note.str();
    }


    void
    GranularScene::finish(const bool last_recorded)
    {
      const auto &p = parameters;
      if (!last_recorded)
        record();
      write_grains();
      if (!p.dem.save_pack.empty())
        save_pack(*dem,
                  p.output.directory,
                  p.dem.save_pack,
                  mpi_communicator,
                  settled ? std::string() : unsettled_note());

      const auto  &s         = last_statistics;
      const double elapsed   = wall_clock.wall_time();
      const double loop_time = loop_clock.wall_time();
      const double grain_steps_per_second =
        (dem->step_number() - first_step) * double(s.n_grains) / loop_time;
      last_results = {
        {"time", dem->time()},
        {"steps", double(dem->step_number())},
        {"grains", double(s.n_grains)},
        {"kinetic_energy", s.kinetic_energy},
        {"mean_speed", s.mean_speed},
        {"max_overlap_ratio", s.max_overlap},
        {"mean_overlap_ratio", s.mean_overlap},
        {"coordination", s.coordination},
        {"packing_fraction", s.packing_fraction},
        {"settled", settled ? 1. : 0.},
        {"settled_servo_max_error", max_servo_error},
        {"lost_grains",
         double(Utilities::MPI::sum(dem->n_lost_grains(), mpi_communicator))},
        {"wall_time", elapsed},
        {"loop_time", loop_time},
        {"grain_steps_per_second", grain_steps_per_second}};
      for (const auto &wall : dem->get_walls())
        {
          last_results[wall.name + "_pressure"] = wall.pressure();
          if (wall.shape == dem::Wall::Shape::plane)
            last_results[wall.name + "_position"] = wall.point * wall.normal;
        }

      console.progress << "softsand granular: " << dem->step_number()
                       << " steps in " << elapsed
                       << " s: " << grain_steps_per_second
                       << " grain-steps/s in the time loop, "
                       << dem->n_neighbor_list_builds()
                       << " neighbour-list builds"
                       << (settled ? ", settled" : "") << std::endl;
      print_results(console.pcout,
                    "granular",
                    last_results,
                    {"wall_time", "loop_time", "grain_steps_per_second"});
    }
  } // namespace drivers
} // namespace softsand
