#ifndef softsand_postprocess_flow_diagnostics_h
#define softsand_postprocess_flow_diagnostics_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <softsand/coupling/grain_solid_field.h>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;
    using BlockVector = TrilinosWrappers::MPI::BlockVector;

    /**
     * Settings of the flow diagnostics: where the pressure drop is measured,
     * the reference velocity of the drag coefficient, and optional exact
     * solutions for error norms (verification scenes).
     */
    struct PostprocessingParameters
    {
      unsigned int        flow_axis = 0;
      std::vector<double> pressure_planes;
      double              reference_velocity = 0;
      std::string         exact_velocity;
      std::string         exact_pressure;
      bool                write_grain_forces = true;
      /// Compute the paper's Eq. 7 force on each grain beside the reaction
      /// force (a diagnostic: one more pass over the cells every step).
      bool                eq7_forces = false;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /// Outward flux int u . n over boundary @p id (m^3/s; m^2/s in 2D).
    template <int dim>
    double
    boundary_flux(const DoFHandler<dim> &dof_handler,
                  const BlockVector     &solution,
                  const unsigned int     boundary_id);

    /// Area of boundary @p id as meshed (m^2; m in 2D): a cylinder's end is
    /// a polygon that approaches the circle as the mesh is refined.
    template <int dim>
    double
    boundary_area(const DoFHandler<dim> &dof_handler,
                  const unsigned int     boundary_id);

    /// Mean pressure over boundary @p id (Pa).
    template <int dim>
    double
    boundary_mean_pressure(const DoFHandler<dim> &dof_handler,
                           const BlockVector     &solution,
                           const unsigned int     boundary_id);

    /// Mean pressure of the fluid (void-fraction weighted) in the slab
    /// |x_axis - position| < half_width (Pa).
    template <int dim>
    double
    slab_mean_pressure(const DoFHandler<dim>           &dof_handler,
                       const BlockVector               &solution,
                       const fluid::SolidField<dim>    *solids,
                       const unsigned int               axis,
                       const double                     position,
                       const double                     half_width);

    /// Force of the fluid on the domain boundary, int (-p I + mu grad u) n:
    /// with the fluid forces on the grains it closes the momentum balance.
    template <int dim>
    Tensor<1, dim>
    boundary_traction(const DoFHandler<dim> &dof_handler,
                      const BlockVector     &solution,
                      const double           viscosity);

    struct Porosity
    {
      /// The paper's: volume fraction of cells with cell void fraction > 0.9.
      double fluid_cell_fraction = 1;
      /// The integral of the cell void fraction over the domain volume.
      double void_fraction_integral = 1;
    };

    /**
     * Porosity of the cells between the planes x_axis = lower and upper
     * (cells cut by a plane count with the part inside), so that a pack with
     * grain-free buffers is measured where its permeability is; the whole
     * domain when lower >= upper.
     */
    template <int dim>
    Porosity
    compute_porosity(const Triangulation<dim>            &tria,
                     const coupling::GrainSolidField<dim> &solids,
                     const unsigned int                    axis  = 0,
                     const double                          lower = 0,
                     const double                          upper = 0);

    /// The pore Reynolds number rho |u| d / mu over the fluid cells (cell
    /// void fraction > 0.9, the paper's fluid cells), |u| the cell's mean
    /// speed: its largest value and the value 95 % of the fluid volume stays
    /// below (read from a histogram of 50 bins per decade: within 5 %).
    struct PoreReynolds
    {
      double max = 0;
      double p95 = 0;
    };

    template <int dim>
    PoreReynolds
    compute_pore_reynolds(const DoFHandler<dim>                &dof_handler,
                          const BlockVector                    &solution,
                          const coupling::GrainSolidField<dim> &solids,
                          const double                          density,
                          const double                          viscosity,
                          const double                          diameter);

    struct ErrorNorms
    {
      double velocity_l2 = 0;
      double velocity_h1_semi = 0;
      /// Pressure error after removing the mean difference.
      double pressure_l2 = 0;
    };

    template <int dim>
    ErrorNorms
    compute_errors(const DoFHandler<dim> &dof_handler,
                   const BlockVector     &solution,
                   const Function<dim>   &exact_solution);
  } // namespace postprocess
} // namespace softsand

#endif
