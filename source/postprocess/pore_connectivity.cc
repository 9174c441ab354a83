#include <deal.II/grid/grid_tools.h>

#include <softsand/postprocess/pore_connectivity.h>

#include <algorithm>
#include <deque>
#include <limits>

namespace softsand
{
  namespace postprocess
  {
    namespace
    {
      /// Which end a box face is on (the bits of PoreConnectivity), 0 for a
      /// face that neither supplies nor takes fluid.
      template <int dim>
      std::array<std::uint8_t, 2 * dim>
      face_ends(const fluid::BoundaryConditions<dim> &bc,
                const std::uint8_t                    inlet,
                const std::uint8_t                    outlet,
                const std::uint8_t                    other)
      {
        using Type = typename fluid::BoundaryConditions<dim>::Type;
        // A face that imposes a flow through it (walls and symmetry do not).
        const auto imposes_flow = [&bc](const unsigned int f) {
          const Type t = bc.face(f).type;
          return t == Type::velocity || t == Type::flow_rate ||
                 t == Type::function;
        };
        std::array<std::uint8_t, 2 * dim> ends{};
        bool   velocity_inlet = false;
        double highest        = -std::numeric_limits<double>::max();
        for (unsigned int f = 0; f < 2 * dim; ++f)
          {
            velocity_inlet = velocity_inlet || imposes_flow(f);
            if (bc.face(f).type == Type::pressure)
              highest = std::max(highest, bc.face(f).pressure);
          }
        const bool region_inlet = bc.inlet_region().enabled();
        for (unsigned int f = 0; f < 2 * dim; ++f)
          {
            if (imposes_flow(f))
              ends[f] = region_inlet ? other : inlet;
            else if (bc.face(f).type == Type::pressure)
              ends[f] = (!region_inlet && !velocity_inlet &&
                         bc.face(f).pressure == highest) ?
                          inlet :
                          outlet;
          }
        return ends;
      }
    } // namespace


    template <int dim>
    PoreConnectivity::PoreConnectivity(
      const parallel::distributed::Triangulation<dim> &mesh,
      const coupling::GrainSolidField<dim>            &solids,
      const fluid::BoundaryConditions<dim>            &bc,
      const OpenCellRule                              &rule)
      : state(mesh.n_active_cells(), 0)
    {
      const auto ends = face_ends(bc, joined_inlet, joined_outlet, joined_other);
      std::uint8_t ends_present = 0;
      for (const auto e : ends)
        ends_present |= e;
      if (bc.inlet_region().enabled())
        ends_present |= joined_inlet;
      if (bc.perimeter_region().enabled())
        ends_present |= joined_outlet;
      has_ends = (ends_present & joined_inlet) && (ends_present & joined_outlet);

      // Open cells (owned and ghost) and the reservoirs they touch.
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          {
            auto &s = state[cell->active_cell_index()];
            if (const auto *region = bc.pressure_region(cell->center()))
              s = open | (region == &bc.inlet_region() ? joined_inlet :
                                                         joined_outlet);
            else if (solids.porous_zone() != nullptr &&
                     solids.porous_zone()->is_porous(*cell))
              s = open; // the hybrid model's porous cells carry flow
            else
              {
                int grain;
                if (rule.is_open(solids.cell_solid_fraction(*cell, grain),
                                 cell->minimum_vertex_distance()))
                  s = open;
              }
            if (s & open)
              for (const unsigned int f : cell->face_indices())
                if (cell->at_boundary(f) &&
                    cell->face(f)->boundary_id() < ends.size())
                  s |= ends[cell->face(f)->boundary_id()];
          }

      // Spread the reservoirs' bits through the open cells, rank by rank,
      // until no rank changes a cell.
      const auto neighbors = [](const auto &cell, auto &&visit) {
        for (const unsigned int f : cell->face_indices())
          if (!cell->at_boundary(f))
            {
              if (cell->face(f)->has_children())
                for (unsigned int c = 0; c < cell->face(f)->n_children(); ++c)
                  visit(cell->neighbor_child_on_subface(f, c));
              else if (cell->neighbor(f)->is_active())
                visit(cell->neighbor(f));
            }
      };
      while (true)
        {
          bool changed = false;
          std::deque<typename Triangulation<dim>::active_cell_iterator> queue;
          for (const auto &cell : mesh.active_cell_iterators())
            if ((cell->is_locally_owned() || cell->is_ghost()) &&
                (state[cell->active_cell_index()] & joined_any))
              queue.push_back(cell);
          while (!queue.empty())
            {
              const auto cell = queue.front();
              queue.pop_front();
              const auto bits = state[cell->active_cell_index()] & joined_any;
              neighbors(cell, [&](const auto &neighbor) {
                if (!neighbor->is_locally_owned())
                  return;
                auto &s = state[neighbor->active_cell_index()];
                if ((s & open) && (s | bits) != s)
                  {
                    s |= bits;
                    changed = true;
                    queue.push_back(neighbor);
                  }
              });
            }
          if (!Utilities::MPI::logical_or(changed, mesh.get_communicator()))
            break;
          GridTools::exchange_cell_data_to_ghosts<
            std::uint8_t,
            parallel::distributed::Triangulation<dim>>(
            mesh,
            [&](const auto &cell) { return state[cell->active_cell_index()]; },
            [&](const auto &cell, const std::uint8_t &s) {
              state[cell->active_cell_index()] = s;
            });
        }

      bool path = false;
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto s = state[cell->active_cell_index()];
            if (!(s & open))
              continue;
            open_volume += cell->measure();
            if (!(s & joined_any))
              sealed_volume += cell->measure();
            path = path || ((s & joined_inlet) && (s & joined_outlet));
          }
      open_volume   = Utilities::MPI::sum(open_volume, mesh.get_communicator());
      sealed_volume = Utilities::MPI::sum(sealed_volume, mesh.get_communicator());
      // A closed container (no inlet, outlet or pressure face): nothing
      // flows through any pore, so none is sealed off from the flow.
      if (ends_present == 0)
        sealed_volume = 0;
      open_path = !has_ends || Utilities::MPI::logical_or(path, mesh.get_communicator());
    }

    template PoreConnectivity::PoreConnectivity(
      const parallel::distributed::Triangulation<2> &,
      const coupling::GrainSolidField<2> &,
      const fluid::BoundaryConditions<2> &,
      const OpenCellRule &);
    template PoreConnectivity::PoreConnectivity(
      const parallel::distributed::Triangulation<3> &,
      const coupling::GrainSolidField<3> &,
      const fluid::BoundaryConditions<3> &,
      const OpenCellRule &);
  } // namespace postprocess
} // namespace softsand
