#include <deal.II/grid/grid_generator.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/version.h>
#include <softsand/base/warnings.h>
#include <softsand/drivers/cylinder_mesh.h>
#include <softsand/drivers/file_mesh.h>
#include <softsand/drivers/scene_setup.h>
#include <softsand/io/column_units.h>
#include <softsand/io/grain_file.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /// Rank 0's log of the scene (the directory made first).
      std::ofstream
      open_log(const std::string &directory,
               const MPI_Comm     comm,
               const bool         append)
      {
        std::ofstream log;
        if (Utilities::MPI::this_mpi_process(comm) != 0)
          return log;
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        log.open(directory + "/log.txt",
                 append ? std::ios::app : std::ios::trunc);
        // Which softsand wrote what follows (a restart appends its own).
        if (log.is_open())
          log << base::version_line() << (append ? ", restarted" : "")
              << std::endl;
        return log;
      }
    } // namespace


    SceneConsole::SceneConsole(const io::OutputParameters &output,
                               const MPI_Comm              comm,
                               const bool                  append)
      : log_file(open_log(output.directory, comm, append))
      , tee_buffer(std::cout.rdbuf(),
                   log_file.is_open() ? log_file.rdbuf() : nullptr)
      , tee(&tee_buffer)
      , log_only(log_file.is_open() ? log_file.rdbuf() : nullptr)
      , pcout(tee, Utilities::MPI::this_mpi_process(comm) == 0)
      // A quiet run keeps its progress in log.txt: a long run in the
      // background can be followed there.
      , progress(output.verbosity == io::OutputParameters::Verbosity::quiet ?
                   log_only :
                   tee,
                 Utilities::MPI::this_mpi_process(comm) == 0 &&
                   (log_file.is_open() ||
                    output.verbosity !=
                      io::OutputParameters::Verbosity::quiet))
    {
      if (log_file.is_open())
        base::set_warning_log(&log_file);
    }


    SceneConsole::~SceneConsole()
    {
      if (log_file.is_open())
        base::set_warning_log(nullptr);
    }


    template <int dim>
    BoundingBox<dim>
    scene_box(const core::MeshParameters<dim> &mesh)
    {
      return BoundingBox<dim>(
        std::make_pair(mesh.lower_corner, mesh.upper_corner));
    }


    void
    make_output_directory(const std::string &directory, const MPI_Comm comm)
    {
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        try
          {
            std::filesystem::create_directories(directory);
          }
        catch (const std::filesystem::filesystem_error &e)
          {
            base::throw_invalid_parameter("output/directory",
                                          directory,
                                          std::string("it cannot be created (") +
                                            e.code().message() +
                                            "): give a writable path");
          }
      MPI_Barrier(comm);
    }


    template <int dim>
    void
    make_domain_mesh(Triangulation<dim>              &triangulation,
                     const core::MeshParameters<dim> &m,
                     const double                     min_diameter)
    {
      if constexpr (dim == 3)
        if (m.geometry == core::MeshParameters<dim>::Geometry::cylinder)
          {
            make_cylinder_mesh(triangulation, m);
            return;
          }
      if (m.geometry == core::MeshParameters<dim>::Geometry::file)
        {
          read_file_mesh(triangulation, m);
          return;
        }
      GridGenerator::subdivided_hyper_rectangle(
        triangulation,
        coarse_subdivisions(m, min_diameter),
        m.lower_corner,
        m.upper_corner,
        true);
    }


    template <int dim>
    std::vector<unsigned int>
    coarse_subdivisions(const core::MeshParameters<dim> &m,
                        const double                     min_diameter)
    {
      std::vector<unsigned int> cells = m.coarse_cells;
      double shortest = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        shortest = std::min(shortest, m.upper_corner[d] - m.lower_corner[d]);
      // Cubes of the shortest edge, or a multiple of them.
      unsigned int per_shortest = 1;
      if (cells.empty() && min_diameter > 0)
        {
          // Octree cells halve per level: the coarse subdivision whose
          // levels come nearest to (not above) the target d_min / N.
          const double ratio = shortest / (min_diameter / m.cells_per_diameter);
          double best_mismatch = std::numeric_limits<double>::max();
          for (int level = 0; level <= 20; ++level)
            {
              const double       per_coarse = std::pow(2., level);
              const unsigned int c =
                std::max(1., std::ceil(ratio / per_coarse - 1e-9));
              if (c > 16)
                continue;
              const double mismatch = c * per_coarse / ratio - 1;
              if (mismatch < best_mismatch - 1e-9)
                {
                  best_mismatch = mismatch;
                  per_shortest  = c;
                }
            }
        }
      if (cells.empty())
        for (unsigned int d = 0; d < dim; ++d)
          cells.push_back(std::max(
            1u,
            static_cast<unsigned int>(
              std::round((m.upper_corner[d] - m.lower_corner[d]) / shortest *
                         per_shortest))));
      return cells;
    }


    namespace
    {
      /// MemTotal of /proc/meminfo in bytes (0 where it cannot be read).
      double
      machine_memory()
      {
        std::ifstream in("/proc/meminfo");
        std::string   name, unit;
        double        kilobytes = 0;
        while (in >> name >> kilobytes >> unit)
          if (name == "MemTotal:")
            return kilobytes * 1024;
        return 0;
      }
    } // namespace


    template <int dim>
    void
    check_memory_estimate(const core::Parameters<dim>        &p,
                          const std::vector<dem::Grain<dim>> &grains,
                          const double                        min_diameter,
                          const MPI_Comm                      comm)
    {
      using Geometry       = typename core::MeshParameters<dim>::Geometry;
      const auto &m        = p.mesh;
      const bool  box      = m.geometry == Geometry::box;
      const bool  resolved = !grains.empty() && m.cells_per_diameter > 0;

      // The coarse mesh, globally refined (a box's; the cylinder's and a
      // mesh file's cells are few and not counted).
      double coarse = 0, coarse_edge = std::numeric_limits<double>::max();
      if (box)
        {
          const auto cells =
            coarse_subdivisions(m, resolved ? min_diameter : 0.);
          coarse = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              coarse *= cells[d];
              coarse_edge =
                std::min(coarse_edge,
                         (m.upper_corner[d] - m.lower_corner[d]) / cells[d]);
            }
        }
      else
        for (unsigned int d = 0; d < dim; ++d)
          coarse_edge =
            std::min(coarse_edge, m.upper_corner[d] - m.lower_corner[d]);
      const double refined = std::pow(2., dim * m.global_refinements);
      const double global  = coarse * refined;
      double       finest  = coarse_edge / std::pow(2., m.global_refinements);
      double       surface = 0; // cells on grain surfaces
      double       uniform = 0; // cells of a uniform refinement
      if (resolved)
        {
          const double target = min_diameter / m.cells_per_diameter;
          const int    levels = std::min<int>(
            std::max(0., std::ceil(std::log2(finest / target) - 1e-9)),
            int(m.max_refinement_level));
          finest /= std::pow(2., levels);
          if (m.uniform_refinement && box)
            uniform = global * std::pow(2., dim * levels);
          else
            {
              // About 4 cells per h^2 of grain surface (an isolated
              // sphere: 10.7 with the 2:1 grading, drag_sphere.prm at
              // N = 8); in a dense pack the grains share their cells: at
              // most half the box refined to h (the 2,000-grain Hele-Shaw
              // pack at N = 4: 4.43 M DoFs, 144 k cells, where the box
              // holds 192 k).
              for (const auto &g : grains)
                surface +=
                  4 * (dim == 3 ? M_PI * std::pow(2 * g.radius / finest, 2) :
                                  M_PI * 2 * g.radius / finest);
              double box_cells = 0.5;
              for (unsigned int d = 0; d < dim; ++d)
                box_cells *= (m.upper_corner[d] - m.lower_corner[d]) / finest;
              surface = std::min(surface, box_cells);
            }
        }
      const double cells         = std::max(global, uniform) + surface;
      const double dofs_per_cell = dim == 3 ? 25 : 9;
      const bool   matrix_free =
        p.fluid_solver.linear_solver ==
        fluid::SolverParameters::LinearSolver::matrix_free;
      const double bytes_per_dof = matrix_free ? 2e3 : 3e3;
      const double dofs          = cells * dofs_per_cell;
      const double bytes         = dofs * bytes_per_dof;

      // This node's share: the ranks that run here.
      MPI_Comm node;
      MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
      const unsigned int ranks_here = Utilities::MPI::n_mpi_processes(node);
      MPI_Comm_free(&node);
      const double here =
        bytes * ranks_here / Utilities::MPI::n_mpi_processes(comm);
      const double memory = Utilities::MPI::min(machine_memory(), comm);
      if (memory <= 0 || here <= memory)
        return;

      // The entry that makes the mesh that large.
      std::string entry, value;
      const auto  list = [](const auto &values) {
        std::ostringstream s;
        for (unsigned int k = 0; k < values.size(); ++k)
          s << (k ? ", " : "") << values[k];
        return s.str();
      };
      if (surface + uniform > global)
        {
          std::ostringstream s;
          s << m.cells_per_diameter;
          entry = "mesh/cells per diameter";
          value = s.str();
        }
      else if (refined > coarse || m.coarse_cells.empty())
        {
          entry = "mesh/global refinements";
          value = std::to_string(m.global_refinements);
        }
      else
        {
          entry = "mesh/coarse cells";
          value = list(m.coarse_cells);
        }
      std::ostringstream why;
      why << std::setprecision(2) << "the fluid mesh would have about " << cells
          << " cells";
      if (surface > 0)
        why << " (" << surface << " on the surfaces of " << grains.size()
            << " grains, about 4 per h^2 with h = " << finest << " m)";
      why << " and " << dofs << " DoFs (" << dofs_per_cell
          << " per cell, Q2-Q1), at about " << bytes_per_dof / 1e3
          << " kB per DoF (" << (matrix_free ? "matrix free" : "matrix based")
          << ") " << std::setprecision(3) << bytes / 1e9 << " GB";
      if (ranks_here < Utilities::MPI::n_mpi_processes(comm))
        why << " (" << here / 1e9 << " GB on this node's " << ranks_here
            << " ranks)";
      why << ", more than this machine's memory, " << memory / 1e9
          << " GB (MemTotal in /proc/meminfo); a low estimate: measured "
             "runs need 3-6 kB per DoF. Coarsen the mesh, or run on more "
             "nodes";
      base::throw_invalid_parameter(entry, value, why.str());
    }


    template <int dim>
    std::unique_ptr<fluid::PenalizedNavierStokes<dim>>
    make_fluid_solver(parallel::distributed::Triangulation<dim> &tria,
                      const core::Parameters<dim> &p,
                      ConditionalOStream          &progress,
                      TimerOutput                 &timer)
    {
      return std::make_unique<fluid::PenalizedNavierStokes<dim>>(
        tria, p.fluid, p.fluid_solver, p.boundary_conditions, progress, timer);
    }


    double
    contact_mesh_cell_size(const std::vector<dem::Grain<3>> &grains,
                           const double                      skin_fraction)
    {
      double r_max = 0;
      for (const auto &g : grains)
        r_max = std::max(r_max, g.radius);
      return std::max(2 * r_max * (1 + 0.5 * skin_fraction), 1e-300);
    }


    BoundingBox<3>
    probe_box(const dem::DEMParameters &dem, const BoundingBox<3> &box)
    {
      const auto &b = dem.probe_box;
      return b.empty() ? box :
                         BoundingBox<3>(std::make_pair(Point<3>(b[0], b[1], b[2]),
                                                       Point<3>(b[3], b[4], b[5])));
    }


    void
    save_pack(const dem::GranularDynamics &dem,
              const std::string           &directory,
              const std::string           &name,
              const MPI_Comm               comm,
              const std::string           &note)
    {
      const auto grains = dem.gather_grains();
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        io::write_grain_file<3>(directory + "/" + name, grains, note);
    }


    template <int dim>
    void
    warn_about_fluid_model(const core::Parameters<dim> &p,
                           const bool                   has_grains,
                           const MPI_Comm               comm)
    {
      if (has_grains && p.fluid.theta == 0 &&
          p.fluid.solid_model == fluid::FluidParameters::SolidModel::penalization)
        base::warn("fluid/theta = 0 with fluid/solid model = penalization: "
                   "the penalty density rho (1 + Theta (1 - vf)) is then rho, "
                   "and the grains hold the fluid only by rho (1 - vf) / dt, "
                   "as if they were fluid (the paper uses Theta = 1e6). Set "
                   "fluid/theta > 0 or fluid/solid model = rigid nodes.",
                   comm);
    }


    void
    add_fluid_row(std::map<std::string, double> &row,
                  const unsigned int             step,
                  const double                   time,
                  const double                   wall_time,
                  io::StatisticsFile            &statistics)
    {
      row["step"]      = step;
      row["time"]      = time;
      row["wall_time"] = wall_time;
      for (const auto &[name, value] : row)
        statistics.add_value(name, value);
    }


    std::string
    progress_of(const double time,
                const double start_time,
                const double end_time,
                const double loop_seconds)
    {
      const double       done = end_time > 0 ? time / end_time : 1;
      const double       run  = time - start_time;
      std::ostringstream s;
      s << std::fixed << std::setprecision(1) << 100 * done
        << " % of the end time";
      if (done > 0 && done < 1 && run > 0)
        s << ", about " << std::setprecision(0)
          << loop_seconds * (end_time - time) / run << " s left";
      return s.str();
    }


    void
    print_results(ConditionalOStream                  &pcout,
                  const std::string                   &title,
                  const std::map<std::string, double> &results,
                  const std::set<std::string>         &left_out,
                  const unsigned int                   dim)
    {
      pcout << "Results (" << title << ", SI units):" << std::endl;
      for (const auto &[name, value] : results)
        if (left_out.count(name) == 0)
          {
            const std::string unit = io::column_unit(name, dim);
            pcout << "  " << std::left << std::setw(27) << name << " "
                  << std::scientific << std::setprecision(5) << value
                  << std::defaultfloat << (unit == "-" ? "" : " " + unit)
                  << std::endl;
          }
    }


    void
    print_fluid_results(ConditionalOStream                  &pcout,
                        const unsigned int                   dim,
                        const std::map<std::string, double> &results)
    {
      std::set<std::string> left_out = {"wall_time",
                                        "linear_iterations",
                                        "nonlinear_iterations",
                                        "total_linear_iterations"};
      if (results.count("radial_flow_rate") != 0)
        for (const char *axial : {"flow_rate",
                                  "outflow_rate",
                                  "permeability",
                                  "pressure_drop",
                                  "superficial_velocity"})
          left_out.insert(axial);
      print_results(pcout, std::to_string(dim) + "D", results, left_out, dim);
    }


    namespace
    {
      /// The files of @p directory, each numbered series as one line
      /// ("solution_####.vtu: 12 files").
      std::string
      output_files(const std::string &directory)
      {
        namespace fs = std::filesystem;
        std::map<std::string, unsigned int> series;
        std::error_code                     error;
        for (const auto &entry : fs::directory_iterator(directory, error))
          {
            std::string name = entry.path().filename().string();
            for (char &c : name)
              if (c >= '0' && c <= '9')
                c = '#';
            ++series[name];
          }
        std::ostringstream out;
        for (const auto &[pattern, count] : series)
          {
            out << "    " << pattern;
            if (count > 1)
              out << ": " << count << " files";
            out << '\n';
          }
        return out.str();
      }
    } // namespace


    void
    print_run_summary(ConditionalOStream                  &pcout,
                      const std::string                   &steps,
                      const double                         time,
                      const std::string                   &end_reason,
                      const std::map<std::string, double> &results,
                      const std::string                   &directory,
                      const MPI_Comm                       comm)
    {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      pcout << "Summary: " << steps << ", t = " << time << " s; ended because "
            << end_reason << "." << std::endl;
      const auto found = [&](const std::string &name) {
        return results.count(name) != 0;
      };
      const auto format = [](const double value) {
        std::ostringstream s;
        s << std::setprecision(4) << value;
        return s.str();
      };
      if (found("fracture_area"))
        pcout << "  fracture: area " << format(1e6 * results.at("fracture_area"))
              << " mm^2 beyond the inlet"
              << (found("fracture_reach") ?
                    ", reach " +
                      format(1e3 * results.at("fracture_reach")) +
                      " mm from the axis" :
                    std::string())
              << std::endl;
      if (found("radial_flow_rate"))
        pcout << "  radial flow rate " << format(results.at("radial_flow_rate"))
              << " m^3/s"
              << (found("pore_reynolds_max") ?
                    ", largest pore Reynolds number " +
                      format(results.at("pore_reynolds_max")) :
                    std::string())
              << std::endl;
      pcout << "  files in " << directory << ":\n"
            << output_files(directory) << std::flush;
    }


#define SOFTSAND_INSTANTIATE(dim)                                               \
  template BoundingBox<dim> scene_box(const core::MeshParameters<dim> &);       \
  template void             make_domain_mesh(Triangulation<dim> &,              \
                                             const core::MeshParameters<dim> &, \
                                             const double);                     \
  template std::unique_ptr<fluid::PenalizedNavierStokes<dim>>                   \
                make_fluid_solver(parallel::distributed::Triangulation<dim> &,  \
                                  const core::Parameters<dim> &,                \
                                  ConditionalOStream &,                         \
                                  TimerOutput &);                               \
  template void warn_about_fluid_model(const core::Parameters<dim> &,           \
                                       const bool,                              \
                                       const MPI_Comm);                         \
  template std::vector<unsigned int> coarse_subdivisions(                       \
    const core::MeshParameters<dim> &, const double);                           \
  template void check_memory_estimate(const core::Parameters<dim> &,            \
                                      const std::vector<dem::Grain<dim>> &,     \
                                      const double,                             \
                                      const MPI_Comm);
    SOFTSAND_INSTANTIATE(2)
    SOFTSAND_INSTANTIATE(3)
#undef SOFTSAND_INSTANTIATE
  } // namespace drivers
} // namespace softsand
