#include <deal.II/grid/grid_generator.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/version.h>
#include <softsand/base/warnings.h>
#include <softsand/drivers/cylinder_mesh.h>
#include <softsand/drivers/file_mesh.h>
#include <softsand/drivers/scene_setup.h>
#include <softsand/io/grain_file.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
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
      GridGenerator::subdivided_hyper_rectangle(
        triangulation, cells, m.lower_corner, m.upper_corner, true);
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
                  const std::set<std::string>         &left_out)
    {
      pcout << "Results (" << title << "):" << std::endl;
      for (const auto &[name, value] : results)
        if (left_out.count(name) == 0)
          pcout << "  " << std::left << std::setw(24) << name << " "
                << std::scientific << std::setprecision(5) << value
                << std::defaultfloat << std::endl;
    }


    void
    print_fluid_results(ConditionalOStream                  &pcout,
                        const unsigned int                   dim,
                        const std::map<std::string, double> &results)
    {
      print_results(pcout,
                    std::to_string(dim) + "D",
                    results,
                    {"wall_time",
                     "linear_iterations",
                     "nonlinear_iterations",
                     "total_linear_iterations"});
    }


#define SOFTSAND_INSTANTIATE(dim)                                             \
  template BoundingBox<dim> scene_box(const core::MeshParameters<dim> &);     \
  template void             make_domain_mesh(Triangulation<dim> &,            \
                                          const core::MeshParameters<dim> &,  \
                                          const double);                      \
  template std::unique_ptr<fluid::PenalizedNavierStokes<dim>>                 \
  make_fluid_solver(parallel::distributed::Triangulation<dim> &,        \
                    const core::Parameters<dim> &,                            \
                    ConditionalOStream &,                                     \
                    TimerOutput &);                                           \
  template void warn_about_fluid_model(const core::Parameters<dim> &,         \
                                       const bool,                            \
                                       const MPI_Comm);
    SOFTSAND_INSTANTIATE(2)
    SOFTSAND_INSTANTIATE(3)
#undef SOFTSAND_INSTANTIATE
  } // namespace drivers
} // namespace softsand
