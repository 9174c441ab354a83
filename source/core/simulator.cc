#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <softsand/core/convergence_study.h>
#include <softsand/core/granular_simulator.h>
#include <softsand/core/parameter_tools.h>
#include <softsand/core/simulator.h>
#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace softsand
{
  namespace core
  {
    template <int dim>
    Simulator<dim>::Simulator(const Parameters<dim> &parameters,
                              const MPI_Comm         comm)
      : parameters(parameters)
      , mpi_communicator(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , progress(std::cout,
                 Utilities::MPI::this_mpi_process(comm) == 0 &&
                   parameters.output.verbosity !=
                     io::OutputParameters::Verbosity::quiet)
      , timer(comm,
              progress,
              TimerOutput::never,
              TimerOutput::wall_times)
      , triangulation(comm,
                      typename Triangulation<dim>::MeshSmoothing(
                        Triangulation<dim>::limit_level_difference_at_vertices))
    {}


    template <int dim>
    void
    Simulator<dim>::make_mesh(const bool refine)
    {
      TimerOutput::Scope t(timer, "mesh");
      const auto        &m = parameters.mesh;
      std::vector<unsigned int> cells = m.coarse_cells;
      const bool resolve_grains = !grains.empty() && m.cells_per_diameter > 0;
      if (cells.empty() && resolve_grains)
        {
          // Octree cells halve per level: choose the coarse subdivision so
          // that some level has exactly (or just below) the target size
          // d_min / N, else N = 8 and N = 12 would give the same mesh.
          const double target =
            solid_field->locator().min_diameter() / m.cells_per_diameter;
          double shortest = std::numeric_limits<double>::max();
          for (unsigned int d = 0; d < dim; ++d)
            shortest = std::min(shortest, m.upper_corner[d] - m.lower_corner[d]);
          const double ratio = shortest / target;
          unsigned int best_cells = 1;
          double       best_mismatch = std::numeric_limits<double>::max();
          for (int level = 0; level <= 20; ++level)
            {
              const double per_coarse = std::pow(2., level);
              const unsigned int c =
                std::max(1., std::ceil(ratio / per_coarse - 1e-9));
              if (c > 16)
                continue;
              const double mismatch = c * per_coarse / ratio - 1;
              if (mismatch < best_mismatch - 1e-9)
                {
                  best_mismatch = mismatch;
                  best_cells    = c;
                }
            }
          for (unsigned int d = 0; d < dim; ++d)
            cells.push_back(std::max(
              1u,
              static_cast<unsigned int>(std::round(
                (m.upper_corner[d] - m.lower_corner[d]) / shortest *
                best_cells))));
        }
      else if (cells.empty())
        {
          double shortest = std::numeric_limits<double>::max();
          for (unsigned int d = 0; d < dim; ++d)
            shortest = std::min(shortest, m.upper_corner[d] - m.lower_corner[d]);
          for (unsigned int d = 0; d < dim; ++d)
            cells.push_back(std::max(
              1u,
              static_cast<unsigned int>(std::round(
                (m.upper_corner[d] - m.lower_corner[d]) / shortest))));
        }
      GridGenerator::subdivided_hyper_rectangle(
        triangulation, cells, m.lower_corner, m.upper_corner, true);
      if (!refine)
        return;
      triangulation.refine_global(m.global_refinements);

      if (resolve_grains &&
          parameters.simulation_control.mode == SimulationControl::Mode::coupled)
        adapt_mesh_to_grains(false);
      else if (resolve_grains)
        {
          const double target =
            solid_field->locator().min_diameter() / m.cells_per_diameter;
          coupling::refine_around_grains(triangulation,
                                         solid_field->locator(),
                                         target,
                                         m.max_refinement_level,
                                         m.uniform_refinement);
        }
    }


    template <int dim>
    void
    Simulator<dim>::run()
    {
      const auto &p = parameters;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        std::filesystem::create_directories(p.output.directory);
      MPI_Barrier(mpi_communicator);
      if (p.simulation_control.mode == SimulationControl::Mode::coupled)
        {
          run_coupled();
          return;
        }

      {
        TimerOutput::Scope t(timer, "grains");
        grains = dem::create_grains(
          p.grains,
          BoundingBox<dim>(
            std::make_pair(p.mesh.lower_corner, p.mesh.upper_corner)));
      }
      solid_field =
        std::make_unique<coupling::GrainSolidField<dim>>(grains, p.void_fraction);
      make_mesh();

      progress << "softsand: " << dim << "D, "
               << Utilities::MPI::n_mpi_processes(mpi_communicator)
               << " MPI rank(s), " << grains.size() << " grain(s), "
               << triangulation.n_global_active_cells() << " cells"
               << std::endl;

      statistics = std::make_unique<io::StatisticsFile>(
        p.output.directory + "/statistics.txt", mpi_communicator);
      if (p.output.write_vtu)
        field_output =
          std::make_unique<io::FieldOutput<dim>>(p.output.directory, "solution");

      fluid = std::make_unique<fluid::PenalizedNavierStokes<dim>>(
        triangulation,
        p.fluid,
        p.fluid_solver,
        p.boundary_conditions,
        progress,
        timer);
      fluid->set_solid_field(grains.empty() ? nullptr : solid_field.get());

      const double dt = p.simulation_control.time_step;
      if (p.simulation_control.is_steady())
        {
          for (unsigned int cycle = 0; cycle <= p.mesh.kelly_cycles; ++cycle)
            {
              if (cycle > 0)
                {
                  TimerOutput::Scope t(timer, "mesh");
                  Vector<float> indicators(triangulation.n_active_cells());
                  const FEValuesExtractors::Vector velocities(0);
                  KellyErrorEstimator<dim>::estimate(
                    fluid->get_dof_handler(),
                    QGauss<dim - 1>(3),
                    {},
                    fluid->get_solution(),
                    indicators,
                    fluid->get_fe().component_mask(velocities));
                  parallel::distributed::GridRefinement::
                    refine_and_coarsen_fixed_number(triangulation,
                                                    indicators,
                                                    p.mesh.kelly_refine_fraction,
                                                    0.);
                  for (const auto &cell : triangulation.active_cell_iterators())
                    if (cell->level() >= int(p.mesh.max_refinement_level))
                      cell->clear_refine_flag();
                  triangulation.execute_coarsening_and_refinement();
                }
              fluid->setup_dofs();
              fluid->set_time(0);
              progress << "   solve " << cycle << ": "
                       << triangulation.n_global_active_cells() << " cells, "
                       << fluid->n_dofs() << " DoFs" << std::endl;
              if (p.simulation_control.mode ==
                  SimulationControl::Mode::steady_stokes)
                fluid->solve_steady_stokes(dt);
              else
                fluid->solve_steady_navier_stokes(dt);
              postprocess(cycle, 0., true);
            }
        }
      else
        {
          fluid->setup_dofs();
          fluid->set_time(0);
          fluid->start_time_stepping();
          double       time = 0;
          unsigned int step = 0;
          while (time < p.simulation_control.end_time * (1 - 1e-12) &&
                 step < p.simulation_control.max_time_steps)
            {
              ++step;
              time += dt;
              fluid->set_time(time);
              fluid->advance(dt, p.simulation_control.bdf_order);
              const bool steady =
                p.simulation_control.steady_state_tolerance > 0 &&
                fluid->relative_velocity_change() <
                  p.simulation_control.steady_state_tolerance;
              const bool last = steady ||
                                time >= p.simulation_control.end_time * (1 - 1e-12) ||
                                step == p.simulation_control.max_time_steps;
              postprocess(step, time, last || step % p.output.output_interval == 0);
              if (step % 10 == 0 || last)
                progress << "   step " << step << ", t = " << time
                         << " s, " << fluid->get_statistics().linear_iterations
                         << " FGMRES iterations, relative change "
                         << fluid->relative_velocity_change() << std::endl;
              if (steady)
                break;
            }
        }
      print_results();
      if (p.output.verbosity != io::OutputParameters::Verbosity::quiet)
        timer.print_wall_time_statistics(mpi_communicator);
    }


    template <int dim>
    void
    Simulator<dim>::postprocess(const unsigned int step,
                                const double       time,
                                const bool         write_fields,
                                const bool         finish_row)
    {
      TimerOutput::Scope t(timer, "postprocess");
      const auto        &p   = parameters;
      const auto        &dof = fluid->get_dof_handler();
      const auto        &u   = fluid->get_solution();
      std::map<std::string, double> r;
      r["step"]                 = step;
      r["time"]                 = time;
      r["cells"]                = triangulation.n_global_active_cells();
      r["dofs"]                 = fluid->n_dofs();
      r["linear_iterations"]    = fluid->get_statistics().linear_iterations;
      r["nonlinear_iterations"] = fluid->get_statistics().nonlinear_iterations;
      // All FGMRES iterations of this solve or step (Newton: every update).
      r["total_linear_iterations"] =
        fluid->get_statistics().total_linear_iterations;

      const unsigned int axis = p.postprocessing.flow_axis;
      const double       mu   = p.fluid.viscosity;
      const double       rho  = p.fluid.density;

      // Forces on grains: the exact discrete reaction and the paper's Eq. (7).
      auto &forces     = grain_forces;
      auto &forces_eq7 = grain_forces_eq7;
      forces           = coupling::GrainForces<dim>();
      forces_eq7       = coupling::GrainForces<dim>();
      if (!grains.empty())
        {
          forces = coupling::compute_grain_forces(
            *fluid, grains, coupling::ForceModel::penalization_reaction,
            mpi_communicator);
          forces_eq7 = coupling::compute_grain_forces(
            *fluid, grains, coupling::ForceModel::stress_divergence,
            mpi_communicator);
        }
      const Tensor<1, dim> total       = forces.total_force();
      const Tensor<1, dim> total_eq7   = forces_eq7.total_force();
      const char           names[3]    = {'x', 'y', 'z'};
      for (unsigned int d = 0; d < dim; ++d)
        {
          r[std::string("grain_force_") + names[d]]     = total[d];
          r[std::string("eq7_grain_force_") + names[d]] = total_eq7[d];
        }
      const Tensor<1, dim> traction =
        postprocess::boundary_traction(dof, u, mu);
      r["boundary_force_" + std::string(1, names[axis])] = traction[axis];
      // The discrete momentum balance: fluid force on grains + on the box
      // faces + body force = 0 (steady), relative to the larger force.
      const Tensor<1, dim> reaction = fluid->boundary_force();
      r["boundary_reaction_" + std::string(1, names[axis])] = reaction[axis];

      // Drag coefficient and Stokes ratio of the first grain.
      double U = p.postprocessing.reference_velocity;
      if (U == 0)
        U = p.boundary_conditions.inflow_velocity().norm();
      if (!grains.empty() && U > 0)
        {
          const double d    = grains[0].diameter();
          const double area = (dim == 3) ? M_PI * d * d / 4 : d;
          const double F    = forces.force[0][axis];
          r["drag_coefficient"] = 2 * F / (rho * U * U * area);
          if (dim == 3)
            {
              r["stokes_drag_ratio"] = F / (3 * M_PI * mu * d * U);
              r["eq7_stokes_drag_ratio"] =
                forces_eq7.force[0][axis] / (3 * M_PI * mu * d * U);
            }
          r["reynolds_number"] = rho * U * d / mu;
        }

      // Pressure drop, flow rate and Darcy permeability K = q mu L / dp.
      double dp = 0, length = 0;
      if (p.postprocessing.pressure_planes.size() == 2)
        {
          const double x1   = p.postprocessing.pressure_planes[0];
          const double x2   = p.postprocessing.pressure_planes[1];
          const double half = 0.5 * coupling::min_cell_edge(triangulation);
          dp = postprocess::slab_mean_pressure(dof, u, solid_field.get(), axis, x1, half) -
               postprocess::slab_mean_pressure(dof, u, solid_field.get(), axis, x2, half);
          length = std::abs(x2 - x1);
        }
      else
        {
          dp     = postprocess::boundary_mean_pressure(dof, u, 2 * axis) -
               postprocess::boundary_mean_pressure(dof, u, 2 * axis + 1);
          length = p.mesh.upper_corner[axis] - p.mesh.lower_corner[axis];
        }
      const double inflow = -postprocess::boundary_flux(dof, u, 2 * axis);
      const double area   = p.boundary_conditions.face_area(2 * axis);
      const double q      = inflow / area;
      r["pressure_drop"]        = dp;
      r["flow_rate"]            = inflow;
      r["superficial_velocity"] = q;
      r["permeability"]         = (dp != 0) ? q * mu * length / dp : 0.;

      if (!grains.empty())
        {
          r["cells_per_diameter"] = solid_field->locator().min_diameter() /
                                    coupling::min_cell_edge(triangulation);
          const auto porosity =
            postprocess::compute_porosity(triangulation, *solid_field);
          r["porosity_cells"]    = porosity.fluid_cell_fraction;
          r["porosity_integral"] = porosity.void_fraction_integral;
          if (p.postprocessing.pressure_planes.size() == 2)
            {
              // Between the planes where K is measured, away from buffers.
              const auto &planes = p.postprocessing.pressure_planes;
              const auto  slab   = postprocess::compute_porosity(
                triangulation,
                *solid_field,
                axis,
                std::min(planes[0], planes[1]),
                std::max(planes[0], planes[1]));
              r["slab_porosity_cells"]    = slab.fluid_cell_fraction;
              r["slab_porosity_integral"] = slab.void_fraction_integral;
            }
        }

      if (!p.postprocessing.exact_velocity.empty())
        {
          FunctionParser<dim> exact(dim + 1);
          exact.initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                           p.postprocessing.exact_velocity + ";" +
                             (p.postprocessing.exact_pressure.empty() ?
                                std::string("0") :
                                p.postprocessing.exact_pressure),
                           core::function_constants(),
                           true);
          exact.set_time(time);
          const auto e = postprocess::compute_errors(dof, u, exact);
          r["velocity_l2_error"] = e.velocity_l2;
          r["velocity_h1_error"] = e.velocity_h1_semi;
          r["pressure_l2_error"] = e.pressure_l2;
        }
      hele_shaw_diagnostics(r, step, write_fields);
      r["wall_time"] = wall_clock.wall_time();

      // Keep the column order stable and readable.
      for (const auto &[name, value] : r)
        statistics->add_value(name, value);
      if (finish_row)
        statistics->write_row();
      last_results = r;

      if (write_fields)
        {
          if (field_output)
            {
              Vector<float> vf(triangulation.n_active_cells());
              for (const auto &cell : triangulation.active_cell_iterators())
                if (cell->is_locally_owned())
                  {
                    int g;
                    vf(cell->active_cell_index()) =
                      1. - solid_field->cell_solid_fraction(*cell, g);
                  }
              field_output->write(dof, u, vf, time);
            }
          if (p.postprocessing.write_grain_forces && !grains.empty() &&
              Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
            {
              const std::string name =
                p.output.directory + "/grain_forces.txt";
              {
                std::ofstream out(name + ".tmp");
                out << "# grain x y" << (dim == 3 ? " z" : "")
                    << " radius fx fy" << (dim == 3 ? " fz" : "")
                    << " tx ty tz eq7_fx eq7_fy" << (dim == 3 ? " eq7_fz" : "")
                    << '\n'
                    << std::setprecision(10);
                for (unsigned int g = 0; g < grains.size(); ++g)
                  {
                    out << g << ' ' << grains[g].center << ' '
                        << grains[g].radius << ' ' << forces.force[g] << ' '
                        << forces.torque[g] << ' ' << forces_eq7.force[g]
                        << '\n';
                  }
              }
              std::rename((name + ".tmp").c_str(), name.c_str());
            }
        }
    }


    template <int dim>
    void
    Simulator<dim>::print_results() const
    {
      // Fixed, deterministic format: tests diff this block with numdiff.
      pcout << "Results (" << dim << "D):" << std::endl;
      for (const auto &[name, value] : last_results)
        if (name != "wall_time" && name != "linear_iterations" &&
            name != "nonlinear_iterations" &&
            name != "total_linear_iterations")
          pcout << "  " << std::left << std::setw(24) << name << " "
                << std::scientific << std::setprecision(5) << value
                << std::defaultfloat << std::endl;
    }


    void
    run_parameter_file(const std::string &filename, const MPI_Comm comm)
    {
      const unsigned int dim = read_dimension(filename);
      const auto         run = [&](auto dim_tag) {
        constexpr int    d = decltype(dim_tag)::value;
        ParameterHandler prm;
        Parameters<d>::declare_parameters(prm);
        prm.parse_input(filename);
        Parameters<d> parameters;
        parameters.parse_parameters(prm);
        if (parameters.convergence_study.knob !=
            ConvergenceStudyParameters::Knob::none)
          {
            ConvergenceStudy<d> study(parameters, comm);
            study.run();
          }
        else if (parameters.simulation_control.mode ==
                 SimulationControl::Mode::granular)
          {
            if constexpr (d == 3)
              {
                GranularSimulator simulator(parameters, comm);
                simulator.run();
              }
            else
              throw_invalid_parameter("simulation control/mode",
                                      "granular",
                                      "granular scenes are 3D (set "
                                      "dimension = 3)");
          }
        else
          {
            Simulator<d> simulator(parameters, comm);
            simulator.run();
          }
      };
      if (dim == 2)
        run(std::integral_constant<int, 2>());
      else
        run(std::integral_constant<int, 3>());
    }

    template class Simulator<2>;
    template class Simulator<3>;
  } // namespace core
} // namespace softsand
