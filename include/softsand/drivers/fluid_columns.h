#ifndef softsand_drivers_fluid_columns_h
#define softsand_drivers_fluid_columns_h

#include <softsand/core/parameters.h>
#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace drivers
  {
    /// The fluid statistics columns a scene's parameters ask for: solver
    /// counts, forces, pressure drop and permeability always; porosity
    /// with grains; errors with an exact solution; radial flow with ring
    /// radii; the fracture area when enabled.
    template <int dim>
    postprocess::FluidColumnList<dim>
    make_fluid_columns(const core::Parameters<dim> &parameters,
                       const MPI_Comm               comm);
  } // namespace drivers
} // namespace softsand

#endif
