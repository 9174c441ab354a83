#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>

#include <softsand/core/granular_simulator.h>
#include <softsand/core/parameter_tools.h>
#include <softsand/dem/pack_generators.h>
#include <softsand/io/grain_file.h>
#include <softsand/io/grain_output.h>
#include <softsand/io/statistics_file.h>
#include <softsand/io/wall_output.h>

#include <cmath>
#include <filesystem>
#include <iomanip>

namespace softsand
{
  namespace core
  {
    GranularSimulator::GranularSimulator(const Parameters<3> &parameters,
                                         const MPI_Comm       comm)
      : parameters(parameters)
      , mpi_communicator(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , progress(std::cout,
                 Utilities::MPI::this_mpi_process(comm) == 0 &&
                   parameters.output.verbosity !=
                     io::OutputParameters::Verbosity::quiet)
      , triangulation(comm)
    {}


    void
    GranularSimulator::make_mesh(const double cell_size)
    {
      dem::make_contact_mesh(
        triangulation,
        BoundingBox<3>(std::make_pair(parameters.mesh.lower_corner,
                                      parameters.mesh.upper_corner)),
        cell_size);
    }


    void
    GranularSimulator::run()
    {
      const auto &p = parameters;
      const auto &dp = p.dem;
      Timer       wall_clock;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        std::filesystem::create_directories(p.output.directory);
      MPI_Barrier(mpi_communicator);

      const BoundingBox<3> domain(
        std::make_pair(p.mesh.lower_corner, p.mesh.upper_corner));
      const std::vector<dem::Grain<3>> grains =
        dem::create_grains(p.grains, domain);
      double r_max = 0;
      for (const auto &g : grains)
        r_max = std::max(r_max, g.radius);
      make_mesh(std::max(2 * r_max * (1 + 0.5 * dp.skin_fraction),
                         1e-300));

      dem = std::make_unique<dem::GranularDynamics>(triangulation, dp, domain);
      dem->insert(grains, true);
      dem->initialize();

      const BoundingBox<3> probe =
        dp.probe_box.empty() ?
          domain :
          BoundingBox<3>(std::make_pair(
            Point<3>(dp.probe_box[0], dp.probe_box[1], dp.probe_box[2]),
            Point<3>(dp.probe_box[3], dp.probe_box[4], dp.probe_box[5])));

      progress << "softsand granular: "
               << Utilities::MPI::n_mpi_processes(mpi_communicator)
               << " MPI rank(s), " << grains.size() << " grain(s), "
               << dem->get_walls().size() << " wall(s), dt = "
               << dem->time_step() << " s = "
               << (dem->rayleigh_time() > 0 ?
                     dem->time_step() / dem->rayleigh_time() :
                     0.)
               << " Rayleigh time" << std::endl;

      io::StatisticsFile statistics(p.output.directory + "/statistics.txt",
                                    mpi_communicator);
      std::unique_ptr<io::GrainOutput> output;
      std::unique_ptr<io::WallOutput>  wall_output;
      if (p.output.write_vtu)
        {
          output =
            std::make_unique<io::GrainOutput>(p.output.directory, "grains");
          if (!dem->get_walls().empty())
            wall_output = std::make_unique<io::WallOutput>(p.output.directory,
                                                           "walls",
                                                           domain);
        }

      dem::GranularStatistics s;
      const auto record = [&]() {
        s = dem->statistics(probe);
        statistics.add_value("time", dem->time());
        statistics.add_value("step", dem->step_number());
        statistics.add_value("kinetic_energy", s.kinetic_energy);
        statistics.add_value("mean_speed", s.mean_speed);
        statistics.add_value("max_speed", s.max_speed);
        statistics.add_value("max_overlap_ratio", s.max_overlap);
        statistics.add_value("mean_overlap_ratio", s.mean_overlap);
        statistics.add_value("max_wall_overlap_ratio", s.max_wall_overlap);
        statistics.add_value("coordination", s.coordination);
        const auto [omega_dt, damping_dt] = dem->stability_rates();
        statistics.add_value("omega_dt", omega_dt);
        statistics.add_value("damping_dt", damping_dt);
        statistics.add_value("packing_fraction", s.packing_fraction);
        statistics.add_value("grains", s.n_grains);
        statistics.add_value("lost_grains",
                             Utilities::MPI::sum(dem->n_lost_grains(),
                                                 mpi_communicator));
        statistics.add_value("neighbor_list_builds",
                             dem->n_neighbor_list_builds());
        for (const auto &wall : dem->get_walls())
          {
            const bool plane = (wall.shape == dem::Wall::Shape::plane);
            // A cylinder's force vector cancels around the axis: its load
            // is the sum of the normal contact forces.
            statistics.add_value(wall.name + "_force_normal",
                                 plane ? -(wall.force * wall.normal) :
                                         wall.normal_force);
            statistics.add_value(wall.name + "_pressure", wall.pressure());
            if (plane)
              statistics.add_value(wall.name + "_position",
                                   wall.point * wall.normal);
          }
        statistics.add_value("wall_time", wall_clock.wall_time());
        statistics.write_row();
      };
      const auto write_grains = [&]() {
        if (output)
          output->write(dem->particles(), dem->time(), mpi_communicator);
        if (wall_output)
          wall_output->write(dem->get_walls(), dem->time(), mpi_communicator);
      };

      if (!dp.save_initial_pack.empty() &&
          Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        io::write_grain_file<3>(p.output.directory + "/" +
                                  dp.save_initial_pack,
                                grains);
      record();
      write_grains();
      Timer loop_clock;
      const double end_time = p.simulation_control.end_time;
      const unsigned long max_steps = p.simulation_control.max_time_steps;
      // The step may adapt: run until the time nearest to the end time.
      const auto finished = [&]() {
        return dem->time() + 0.5 * dem->time_step() >= end_time ||
               dem->step_number() >= max_steps;
      };
      unsigned int settled_rows = 0;
      double       max_servo_error = 0; // over the settled rows
      bool         settled      = false;
      double       next_report  = 10;
      bool last_recorded = true;
      while (!finished())
        {
          dem->step();
          const unsigned long n = dem->step_number();
          last_recorded = (n % dp.statistics_interval == 0) || finished();
          if (last_recorded)
            {
              record();
              // Settled: little motion and every servo wall at its target.
              double servo_error = 0;
              for (const auto &wall : dem->get_walls())
                if (wall.motion == dem::Wall::Motion::servo)
                  servo_error = std::max(
                    servo_error,
                    std::abs(wall.pressure() / wall.target_pressure - 1));
              if (dp.settled_kinetic_energy > 0 && s.n_grains > 0 &&
                  s.kinetic_energy / s.n_grains < dp.settled_kinetic_energy &&
                  servo_error < dp.walls.servo_tolerance)
                {
                  max_servo_error = std::max(max_servo_error, servo_error);
                  if (++settled_rows >= dp.settled_checks)
                    settled = true;
                }
              else
                {
                  settled_rows    = 0;
                  max_servo_error = 0;
                }
            }
          if (dp.output_interval > 0 && n % dp.output_interval == 0)
            write_grains();
          if (wall_clock.wall_time() > next_report)
            {
              progress << "  t = " << dem->time() << " s of " << end_time
                       << ", step " << n << ", dt " << dem->time_step()
                       << " s, kinetic energy "
                       << s.kinetic_energy << " J, "
                       << std::setprecision(3)
                       << n * s.n_grains / wall_clock.wall_time()
                       << " grain-steps/s" << std::setprecision(6)
                       << std::endl;
              next_report += 10;
            }
          if (settled)
            break;
        }
      if (!last_recorded)
        record();
      write_grains();

      if (!dp.save_pack.empty())
        {
          const auto final_grains = dem->gather_grains();
          if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
            io::write_grain_file<3>(p.output.directory + "/" + dp.save_pack,
                                    final_grains);
        }

      const double elapsed   = wall_clock.wall_time();
      const double loop_time = loop_clock.wall_time();
      last_results = {{"time", dem->time()},
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
                      {"lost_grains", double(Utilities::MPI::sum(
                                        dem->n_lost_grains(), mpi_communicator))},
                      {"wall_time", elapsed},
                      {"loop_time", loop_time},
                      {"grain_steps_per_second",
                       dem->step_number() * double(s.n_grains) / loop_time}};
      for (const auto &wall : dem->get_walls())
        {
          last_results[wall.name + "_pressure"] = wall.pressure();
          if (wall.shape == dem::Wall::Shape::plane)
            last_results[wall.name + "_position"] = wall.point * wall.normal;
        }

      progress << "softsand granular: " << dem->step_number() << " steps in "
               << elapsed << " s: "
               << dem->step_number() * double(s.n_grains) / loop_time
               << " grain-steps/s in the time loop, " << dem->n_neighbor_list_builds()
               << " neighbour-list builds"
               << (settled ? ", settled" : "") << std::endl;
      pcout << "Results (granular):" << std::endl;
      for (const auto &[name, value] : last_results)
        if (name != "wall_time" && name != "loop_time" &&
            name != "grain_steps_per_second")
          pcout << "  " << std::left << std::setw(24) << name << " "
                << std::scientific << std::setprecision(5) << value
                << std::defaultfloat << std::endl;
    }
  } // namespace core
} // namespace softsand
