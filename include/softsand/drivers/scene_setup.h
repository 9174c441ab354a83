#ifndef softsand_drivers_scene_setup_h
#define softsand_drivers_scene_setup_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <softsand/base/tee_stream.h>
#include <softsand/core/parameters.h>
#include <softsand/dem/granular_dynamics.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/io/statistics_file.h>

#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    /**
     * The screens of a scene: results (rank 0) and progress (rank 0, unless
     * output/verbosity = quiet), both also written to the output
     * directory's log.txt with the warnings; a restarted run (@p append)
     * adds to the log.
     */
    class SceneConsole
    {
    public:
      SceneConsole(const io::OutputParameters &output,
                   const MPI_Comm              comm,
                   const bool                  append = false);
      ~SceneConsole();

    private:
      std::ofstream   log_file;
      base::TeeBuffer tee_buffer;
      std::ostream    tee;
      /// The log alone: where the progress of a quiet run goes.
      std::ostream    log_only;

    public:
      ConditionalOStream pcout;
      ConditionalOStream progress;
    };

    /// The scene's box.
    template <int dim>
    BoundingBox<dim>
    scene_box(const core::MeshParameters<dim> &mesh);

    /// Creates the output directory (rank 0); every rank waits for it.
    void
    make_output_directory(const std::string &directory, const MPI_Comm comm);

    /**
     * The coarse mesh of the domain: for a box the cells of mesh/coarse
     * cells, or cubes of the shortest edge. Where grains are resolved
     * (@p min_diameter > 0), the subdivision is chosen so that some octree
     * level has cells of exactly (or just below) d_min / N, else N = 8 and
     * N = 12 would give the same mesh. For a cylinder: make_cylinder_mesh.
     */
    template <int dim>
    void
    make_domain_mesh(Triangulation<dim>              &triangulation,
                  const core::MeshParameters<dim> &mesh,
                  const double                     min_diameter);

    /// The coarse cells per direction of a box domain, as make_domain_mesh()
    /// makes them.
    template <int dim>
    std::vector<unsigned int>
    coarse_subdivisions(const core::MeshParameters<dim> &mesh,
                        const double                     min_diameter);

    /**
     * Stops the run before its fluid mesh is built when a rough estimate of
     * the fluid's memory exceeds the machine's (MemTotal of /proc/meminfo;
     * with several ranks, this node's share of the estimate), with a
     * message naming the entry that makes the mesh that large, the
     * estimate and the machine's memory. Without the check, a mesh of
     * coarse cells = 2000, 2000, 2000 or cells per diameter = 256 grew
     * until the machine ran out of memory. The estimate is low rather than
     * high (it refuses no run that fits): the coarse cells times 2^(dim g)
     * for g global refinements, refined uniformly, or by about 4 cells per
     * h^2 of grain surface (h the finest cell; an isolated sphere has
     * 10.7), at most half the box's volume in cells of h (dense packs share
     * cells), 25 DoFs per cell in 3D (9 in 2D, Q2-Q1) and 3 kB per DoF
     * (2 kB matrix free; measured 3-6 kB, user_guide.md "Sizing").
     */
    template <int dim>
    void
    check_memory_estimate(const core::Parameters<dim>        &parameters,
                          const std::vector<dem::Grain<dim>> &grains,
                          const double                        min_diameter,
                          const MPI_Comm                      comm);

    /// The penalized Navier-Stokes solver of a scene on @p triangulation.
    template <int dim>
    std::unique_ptr<fluid::PenalizedNavierStokes<dim>>
    make_fluid_solver(parallel::distributed::Triangulation<dim> &tria,
                      const core::Parameters<dim> &parameters,
                      ConditionalOStream          &progress,
                      TimerOutput                 &timer);

    /// Cell size of the DEM's mesh: one contact range, 2 r_max (1 + skin /
    /// 2), so that its ghost layer of one cell is the contact halo.
    double
    contact_mesh_cell_size(const std::vector<dem::Grain<3>> &grains,
                           const double                      skin_fraction);

    /// The box where the packing fraction is measured (dem/probe box, or
    /// the scene's box).
    BoundingBox<3>
    probe_box(const dem::DEMParameters &dem, const BoundingBox<3> &box);

    /// Writes the DEM's grains as a pack file (rank 0) to
    /// @p directory/@p name, with @p note in its header.
    void
    save_pack(const dem::GranularDynamics &dem,
              const std::string           &directory,
              const std::string           &name,
              const MPI_Comm               comm,
              const std::string           &note = "");

    /// Warns (once) where the fluid model on these grains is outside its
    /// validity: penalization with Theta = 0 does not hold the fluid.
    template <int dim>
    void
    warn_about_fluid_model(const core::Parameters<dim> &parameters,
                           const bool                   has_grains,
                           const MPI_Comm               comm);

    /// A fluid row: @p row with the step, time and wall time added, into
    /// the statistics file (in the order of the names).
    void
    add_fluid_row(std::map<std::string, double> &row,
                  const unsigned int             step,
                  const double                   time,
                  const double                   wall_time,
                  io::StatisticsFile            &statistics);

    /// For progress lines: "P % of the end time, about S s left" from the
    /// time reached and the wall time its loop took since it started at
    /// @p start_time (a restarted run's rate is that of its own steps).
    std::string
    progress_of(const double time,
                const double start_time,
                const double end_time,
                const double loop_seconds);

    /// The results block ("Results (TITLE, SI units):"), one line per
    /// entry of @p results but those @p left_out (timings, counts): name,
    /// value and its unit (none for a pure number). Scripts read it.
    void
    print_results(ConditionalOStream                  &pcout,
                  const std::string                   &title,
                  const std::map<std::string, double> &results,
                  const std::set<std::string>         &left_out,
                  const unsigned int                   dim = 3);

    /// The results block of a fluid or coupled scene ("Results (3D):"),
    /// without the wall time and the solver counts, which vary with the
    /// machine and the solver rather than the physics, and without the
    /// axial flow's columns (flow rate, permeability, pressure drop) in a
    /// radial injection, where they are zero by construction.
    void
    print_fluid_results(ConditionalOStream                  &pcout,
                        const unsigned int                   dim,
                        const std::map<std::string, double> &results);

    /// What a person reads at the end of a run: how far it went, why it
    /// ended, the fracture in mm and mm^2 (when measured) and the files
    /// in @p directory, numbered series counted rather than listed.
    void
    print_run_summary(ConditionalOStream                  &pcout,
                      const std::string                   &steps,
                      const double                         time,
                      const std::string                   &end_reason,
                      const std::map<std::string, double> &results,
                      const std::string                   &directory,
                      const MPI_Comm                       comm);
  } // namespace drivers
} // namespace softsand

#endif
