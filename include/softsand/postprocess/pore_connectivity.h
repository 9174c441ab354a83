#ifndef softsand_postprocess_pore_connectivity_h
#define softsand_postprocess_pore_connectivity_h

#include <deal.II/distributed/tria.h>

#include <softsand/coupling/grain_solid_field.h>
#include <softsand/fluid/boundary_conditions.h>

#include <cstdint>
#include <vector>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * Which cells carry flow. The paper's cell-average penalization makes a
     * covered fraction sf of a cell a Brinkman resistance
     * rho (1 + Theta sf) sf / dt; the cell is open while that stays below
     * its viscous resistance mu / h^2 (Brinkman number < 1): at Theta 1e6
     * only uncovered cells are. The other rules (rigid nodes, cell
     * majority, quadrature points) leave the fluid the uncovered part of a
     * cell: open while sf < 1/2.
     */
    struct OpenCellRule
    {
      bool   brinkman = false;
      double density = 0, viscosity = 1, theta = 0, time_step = 1;

      bool
      is_open(const double solid_fraction, const double cell_edge) const
      {
        if (!brinkman)
          return solid_fraction < 0.5;
        return density * (1 + theta * solid_fraction) * solid_fraction *
                 cell_edge * cell_edge <
               viscosity * time_step;
      }
    };

    /**
     * The open cells (OpenCellRule) and how their face-connected
     * components reach the scene's reservoirs: the inlet end (the inlet
     * region; else the faces imposing a velocity or flow rate; else the
     * pressure faces at the highest pressure), the outlet end (the perimeter
     * region and the other pressure faces) and the other velocity faces.
     * An open component that reaches none is a sealed pocket: no flow
     * enters it and its pressure floats. Pressure-region cells are open.
     */
    class PoreConnectivity
    {
    public:
      template <int dim>
      PoreConnectivity(const parallel::distributed::Triangulation<dim> &mesh,
                       const coupling::GrainSolidField<dim>            &solids,
                       const fluid::BoundaryConditions<dim> &boundaries,
                       const OpenCellRule                   &rule);

      /// Volume (m^3; m^2 in 2D) of the open cells, and of those that no
      /// open path joins to a reservoir.
      double open_volume = 0, sealed_volume = 0;
      /// Whether the scene has an inlet end and an outlet end, and whether
      /// an open path joins them.
      bool has_ends = false, open_path = true;

      /// Whether the cell (locally owned) is open and joined to a reservoir:
      /// the connected pore space, where mean pressures are taken.
      bool
      connected(const unsigned int active_cell_index) const
      {
        const auto s = state[active_cell_index];
        return (s & open) && (s & joined_any);
      }
      bool
      sealed(const unsigned int active_cell_index) const
      {
        const auto s = state[active_cell_index];
        return (s & open) && !(s & joined_any);
      }

    private:
      static constexpr std::uint8_t joined_inlet = 1, joined_outlet = 2,
                                    joined_other = 4, open = 8;
      static constexpr std::uint8_t joined_any =
        joined_inlet | joined_outlet | joined_other;
      /// Per active cell: the bits above.
      std::vector<std::uint8_t> state;
    };
  } // namespace postprocess
} // namespace softsand

#endif
