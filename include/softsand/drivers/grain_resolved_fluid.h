#ifndef softsand_drivers_grain_resolved_fluid_h
#define softsand_drivers_grain_resolved_fluid_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <softsand/core/parameters.h>
#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_solid_field.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/io/field_output.h>
#include <softsand/postprocess/columns/fluid_column_source.h>

#include <memory>
#include <vector>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    /**
     * The fluid part of a scene, shared by the fixed-grain and the coupled
     * scenes: the octree mesh fitted to the grains, the grains' solid field,
     * the penalized Navier-Stokes solver on it and what follows a solve (the
     * fluid forces on the grains, the fluid statistics columns, the field
     * and grain-force files).
     */
    template <int dim>
    class GrainResolvedFluid
    {
    public:
      GrainResolvedFluid(const core::Parameters<dim> &parameters,
                         const MPI_Comm               comm,
                         ConditionalOStream          &progress,
                         TimerOutput                 &timer);

      /// The grains the fluid flows around; their solid field is rebuilt
      /// (and handed to the solver once it exists).
      void
      set_grains(std::vector<dem::Grain<dim>> new_grains);

      /// Mesh partition weights: a cell cut by a grain surface costs more to
      /// assemble (grains at its quadrature points) than a plain cell.
      void
      weight_cut_cells(const double extra_weight);

      /**
       * The box mesh. With @p refine, refined globally and then around the
       * grains: once to the surface cell size (@p follow_grains false), or
       * by adapt_to_grains() (a margin, coarsening too). A restart loads
       * the refinement instead.
       */
      void
      make_mesh(const bool refine, const bool follow_grains);

      /// Refine and coarsen until the mesh fits the grains, the fluid
      /// fields transferred (@p transfer) to the new mesh; the number of
      /// sweeps.
      unsigned int
      adapt_to_grains(const bool transfer);

      /// Largest grain displacement since the last adapt_to_grains().
      double
      max_displacement_since_adaptation() const;

      /// The fluid solver (and the field output) on the mesh.
      void
      create_solver(const bool moving_solids);

      /// A restarted run: the field files continue the series at @p time.
      void
      resume_field_output(const double time)
      {
        if (field_output)
          field_output->resume(time);
      }

      /**
       * After a solve: the fluid forces on the grains and the statistics
       * columns of the row; with @p write_files, the field and grain-force
       * files too.
       */
      postprocess::Columns
      postprocess(const unsigned int step,
                  const double       time,
                  const bool         write_files);

      /// The files of step 0 (fields, fracture map) at @p time, before the
      /// first solve; no statistics row.
      void
      write_initial_state(const double time);

      parallel::distributed::Triangulation<dim> &
      triangulation()
      {
        return mesh;
      }
      const parallel::distributed::Triangulation<dim> &
      triangulation() const
      {
        return mesh;
      }
      fluid::PenalizedNavierStokes<dim> &
      solver()
      {
        return *navier_stokes;
      }
      const fluid::PenalizedNavierStokes<dim> &
      solver() const
      {
        return *navier_stokes;
      }
      const std::vector<dem::Grain<dim>> &
      grains() const
      {
        return grain_list;
      }
      const coupling::GrainSolidField<dim> &
      solid_field() const
      {
        return *solids;
      }
      /// The forces of the last postprocess(): the discrete reaction and
      /// the paper's Eq. (7).
      const coupling::GrainForces<dim> &
      forces() const
      {
        return reaction_forces;
      }
      const coupling::GrainForces<dim> &
      forces_eq7() const
      {
        return eq7_forces;
      }
      /// Where the grains were at the last adaptation (checkpointed).
      const std::vector<Point<dim>> &
      centers_at_adaptation() const
      {
        return adaptation_centers;
      }
      void
      set_centers_at_adaptation(const std::vector<Point<dim>> &centers)
      {
        adaptation_centers = centers;
      }

    private:
      /// Stops when the finest cells are too coarse for the grains, unless
      /// mesh/allow unresolved grains.
      void
      check_resolution() const;
      void
      write_fields(const unsigned int step, const double time) const;
      void
      write_grain_forces() const;

      const core::Parameters<dim> &parameters;
      const MPI_Comm               mpi_communicator;
      ConditionalOStream          &progress;
      TimerOutput                 &timer;

      parallel::distributed::Triangulation<dim>           mesh;
      std::vector<dem::Grain<dim>>                        grain_list;
      std::unique_ptr<coupling::GrainSolidField<dim>>     solids;

      /// The grains' solid field of grain_list, with the hybrid model's
      /// porous zone when the scene asks for it.
      std::unique_ptr<coupling::GrainSolidField<dim>>
      make_solid_field() const;

      /// resolved_grain_fraction, porous_cell_fraction (hybrid model).
      void
      add_hybrid_columns(const coupling::PorousZone<dim> &zone,
                         postprocess::Columns            &row) const;
      std::unique_ptr<fluid::PenalizedNavierStokes<dim>>  navier_stokes;
      std::unique_ptr<io::FieldOutput<dim>>               field_output;
      const postprocess::FluidColumnList<dim>             columns;
      coupling::GrainForces<dim>                          reaction_forces;
      coupling::GrainForces<dim>                          eq7_forces;
      /// The open pore space of the last postprocessed solution.
      std::unique_ptr<postprocess::PoreConnectivity>      pores;
      std::vector<Point<dim>>                             adaptation_centers;
    };
  } // namespace drivers
} // namespace softsand

#endif
