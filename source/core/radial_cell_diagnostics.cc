// Diagnostics of radial cells (the Hele-Shaw injection, the paper's
// section 4): pressure rings, radial flow rate and Darcy permeability around
// the inlet, and the area of the open channels connected to it (Fig. 9).

#include <softsand/core/simulator.h>
#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/postprocess/fracture_area.h>
#include <softsand/postprocess/radial_flow.h>

#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace core
  {
    template <int dim>
    void
    Simulator<dim>::hele_shaw_diagnostics(std::map<std::string, double> &r,
                                          const unsigned int             step,
                                          const bool write_fields) const
    {
      const auto &p     = parameters;
      const auto &inlet = p.boundary_conditions.inlet_region();
      // Pressure rings, flow rates and Darcy permeability around the inlet.
      const auto &radii = p.radial_flow.radii;
      if (radii.size() >= 2)
        {
          const double half_width =
            p.radial_flow.ring_half_width > 0 ?
              p.radial_flow.ring_half_width :
              0.5 * coupling::min_cell_edge(triangulation);
          const auto flow = postprocess::compute_radial_flow(
            fluid->get_dof_handler(),
            fluid->get_solution(),
            grains.empty() ? nullptr : solid_field.get(),
            inlet,
            radii,
            half_width);
          // Layer thickness: the box along the inlet axis.
          double thickness = 1;
          if (dim == 3)
            {
              const Tensor<1, dim> extent =
                p.mesh.upper_corner - p.mesh.lower_corner;
              thickness = 0;
              for (unsigned int d = 0; d < dim; ++d)
                thickness += std::abs(extent[d] * inlet.axis[d]);
            }
          const double mu = p.fluid.viscosity;
          for (unsigned int k = 0; k < radii.size(); ++k)
            {
              r["ring_pressure_" + std::to_string(k)] = flow.ring_pressure[k];
              if (k + 1 < radii.size())
                r["radial_permeability_" + std::to_string(k)] =
                  flow.permeability(
                    radii, k, k + 1, flow.flow_rate[k], mu, thickness);
            }
          r["radial_flow_rate"] = flow.total_flow_rate;
          r["radial_permeability"] = flow.permeability(
            radii, 0, radii.size() - 1, flow.total_flow_rate, mu, thickness);
        }

      // Area of the open channels connected to the inlet (the paper's Fig.
      // 9), computed on rank 0 from the grains (every rank holds them).
      if constexpr (dim == 3)
        if (p.fracture_area.enabled)
          {
            double areas[2] = {0, 0};
            if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              {
                const auto &lo = p.mesh.lower_corner;
                const auto &hi = p.mesh.upper_corner;
                const postprocess::FractureMap map(
                  grains,
                  Point<2>(lo[0], lo[1]),
                  Point<2>(hi[0], hi[1]),
                  lo[2],
                  hi[2],
                  Point<2>(inlet.center[0], inlet.center[1]),
                  inlet.radius,
                  p.fracture_area);
                areas[0] = map.fracture_area();
                areas[1] = map.open_area();
                if (write_fields && p.output.write_vtu)
                  {
                    std::ostringstream name;
                    name << p.output.directory << "/fracture_map-"
                         << std::setw(5) << std::setfill('0') << step
                         << ".pgm";
                    map.write_pgm(name.str());
                  }
              }
            MPI_Bcast(areas, 2, MPI_DOUBLE, 0, mpi_communicator);
            r["fracture_area"] = areas[0];
            r["open_area"]     = areas[1];
          }
    }


    template void
    Simulator<2>::hele_shaw_diagnostics(std::map<std::string, double> &,
                                        const unsigned int,
                                        const bool) const;
    template void
    Simulator<3>::hele_shaw_diagnostics(std::map<std::string, double> &,
                                        const unsigned int,
                                        const bool) const;
  } // namespace core
} // namespace softsand
