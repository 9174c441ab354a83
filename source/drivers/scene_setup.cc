#include <deal.II/grid/grid_generator.h>

#include <softsand/drivers/scene_setup.h>
#include <softsand/io/grain_file.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>

namespace softsand
{
  namespace drivers
  {
    SceneConsole::SceneConsole(const io::OutputParameters &output,
                               const MPI_Comm              comm)
      : pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , progress(std::cout,
                 Utilities::MPI::this_mpi_process(comm) == 0 &&
                   output.verbosity != io::OutputParameters::Verbosity::quiet)
    {}


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
        std::filesystem::create_directories(directory);
      MPI_Barrier(comm);
    }


    template <int dim>
    void
    make_box_mesh(Triangulation<dim>              &triangulation,
                  const core::MeshParameters<dim> &m,
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
              const MPI_Comm               comm)
    {
      const auto grains = dem.gather_grains();
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        io::write_grain_file<3>(directory + "/" + name, grains);
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
  template void             make_box_mesh(Triangulation<dim> &,               \
                                          const core::MeshParameters<dim> &,  \
                                          const double);                      \
  template std::unique_ptr<fluid::PenalizedNavierStokes<dim>>                 \
  make_fluid_solver(parallel::distributed::Triangulation<dim> &,        \
                    const core::Parameters<dim> &,                            \
                    ConditionalOStream &,                                     \
                    TimerOutput &);
    SOFTSAND_INSTANTIATE(2)
    SOFTSAND_INSTANTIATE(3)
#undef SOFTSAND_INSTANTIATE
  } // namespace drivers
} // namespace softsand
