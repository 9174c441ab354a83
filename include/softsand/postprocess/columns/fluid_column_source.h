#ifndef softsand_postprocess_columns_fluid_column_source_h
#define softsand_postprocess_columns_fluid_column_source_h

#include <deal.II/distributed/tria.h>

#include <softsand/coupling/grain_forces.h>
#include <softsand/coupling/grain_solid_field.h>
#include <softsand/dem/grain.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/postprocess/pore_connectivity.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;

    /// A statistics row under construction: column name -> value.
    using Columns = std::map<std::string, double>;

    /// What the fluid column sources read after a solve: the fluid on its
    /// mesh, the grains it flows around and their fluid forces.
    template <int dim>
    struct FluidSnapshot
    {
      const parallel::distributed::Triangulation<dim> &triangulation;
      const fluid::PenalizedNavierStokes<dim>         &fluid;
      const std::vector<dem::Grain<dim>>              &grains;
      const coupling::GrainSolidField<dim>            &solid_field;
      /// The exact discrete reaction and the paper's Eq. (7) (diagnostic).
      const coupling::GrainForces<dim> &forces;
      const coupling::GrainForces<dim> &forces_eq7;
      unsigned int                      step;
      double                            time;
      /// Field output is due at this row (sources with files write them).
      bool write_fields;
      /// The open cells and the pockets among them (nullptr without
      /// grains).
      const PoreConnectivity *pores;
    };

    /**
     * One group of statistics columns of a fluid scene: it takes its
     * settings when constructed and
     * adds its columns to each row. A scene holds the sources its
     * parameters ask for (drivers::make_fluid_columns).
     */
    template <int dim>
    class FluidColumnSource
    {
    public:
      virtual ~FluidColumnSource() = default;

      virtual void
      add_columns(const FluidSnapshot<dim> &snapshot, Columns &row) const = 0;

      /// The files of the initial state (step 0, before any solve) of a
      /// source that writes files: no columns, no row.
      virtual void
      write_initial_files(const FluidSnapshot<dim> &) const
      {}
    };

    template <int dim>
    using FluidColumnList =
      std::vector<std::unique_ptr<const FluidColumnSource<dim>>>;
  } // namespace postprocess
} // namespace softsand

#endif
