#include <softsand/drivers/fluid_columns.h>
#include <softsand/postprocess/columns/error_columns.h>
#include <softsand/postprocess/columns/flow_regime_columns.h>
#include <softsand/postprocess/columns/force_columns.h>
#include <softsand/postprocess/columns/fracture_area_columns.h>
#include <softsand/postprocess/columns/permeability_columns.h>
#include <softsand/postprocess/columns/pore_space_columns.h>
#include <softsand/postprocess/columns/porosity_columns.h>
#include <softsand/postprocess/columns/radial_flow_columns.h>
#include <softsand/postprocess/columns/solver_columns.h>

#include <cmath>

namespace softsand
{
  namespace drivers
  {
    template <int dim>
    postprocess::FluidColumnList<dim>
    make_fluid_columns(const core::Parameters<dim> &p, const MPI_Comm comm)
    {
      using namespace postprocess;
      const auto        &pp   = p.postprocessing;
      const unsigned int axis = pp.flow_axis;
      const double       mu   = p.fluid.viscosity;
      FluidColumnList<dim> columns;
      columns.emplace_back(std::make_unique<SolverColumns<dim>>());

      const double U = pp.reference_velocity != 0 ?
                         pp.reference_velocity :
                         p.boundary_conditions.inflow_velocity().norm();
      columns.emplace_back(
        std::make_unique<ForceColumns<dim>>(axis, mu, p.fluid.density, U));
      columns.emplace_back(std::make_unique<PermeabilityColumns<dim>>(
        axis,
        mu,
        pp.pressure_planes,
        p.mesh.upper_corner[axis] - p.mesh.lower_corner[axis]));
      columns.emplace_back(
        std::make_unique<PorosityColumns<dim>>(axis, pp.pressure_planes));
      // The entry that chose a model without inertia, named by the
      // flow-regime warning.
      using Mode = core::SimulationControl::Mode;
      std::string creeping_model, inertial_model;
      if (p.simulation_control.mode == Mode::steady_stokes)
        {
          creeping_model = "simulation control/mode = steady stokes";
          inertial_model = "simulation control/mode = steady navier stokes";
        }
      else if (p.simulation_control.mode == Mode::coupled &&
               p.coupling.fluid_model ==
                 coupling::CouplingParameters::FluidModel::quasi_steady)
        {
          creeping_model = "coupling/fluid model = quasi-steady";
          inertial_model = "coupling/fluid model = transient";
        }
      columns.emplace_back(std::make_unique<PoreSpaceColumns<dim>>());
      columns.emplace_back(std::make_unique<FlowRegimeColumns<dim>>(
        p.fluid.density, mu, creeping_model, inertial_model));
      if (!pp.exact_velocity.empty())
        columns.emplace_back(std::make_unique<ErrorColumns<dim>>(
          pp.exact_velocity, pp.exact_pressure));

      const auto &inlet = p.boundary_conditions.inlet_region();
      if (p.radial_flow.radii.size() >= 2)
        {
          // The layer between the plates: the box along the inlet axis.
          double thickness = 1;
          if (dim == 3)
            {
              const Tensor<1, dim> extent =
                p.mesh.upper_corner - p.mesh.lower_corner;
              thickness = 0;
              for (unsigned int d = 0; d < dim; ++d)
                thickness += std::abs(extent[d] * inlet.axis[d]);
            }
          columns.emplace_back(std::make_unique<RadialFlowColumns<dim>>(
            p.radial_flow, inlet, thickness, p.fluid.density, mu));
        }
      // Parameters<dim> allows the fracture map in 3D only.
      if constexpr (dim == 3)
        if (p.fracture_area.enabled)
          columns.emplace_back(std::make_unique<FractureAreaColumns>(
            p.fracture_area,
            inlet,
            p.mesh.lower_corner,
            p.mesh.upper_corner,
            p.output.write_vtu ? p.output.directory : std::string(),
            comm));
      return columns;
    }

    template postprocess::FluidColumnList<2>
    make_fluid_columns(const core::Parameters<2> &, const MPI_Comm);
    template postprocess::FluidColumnList<3>
    make_fluid_columns(const core::Parameters<3> &, const MPI_Comm);
  } // namespace drivers
} // namespace softsand
