// PenalizedNavierStokes: the grains' constraints. Which velocity nodes the
// grains fix (rigid nodes) or leave to the fluid (free contact cells), the
// solid fraction at the nodes, and the pressures grains enclose.

#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/penalization_limit.h>
#include <softsand/fluid/penalized_navier_stokes.h>
#include <softsand/base/parameter_tools.h>
#include <softsand/base/warnings.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>
#include <set>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_solid_field(const SolidField<dim> *solids)
    {
      solid_field = solids;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::set_moving_solids(const bool moving)
    {
      moving_solids = moving;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::find_velocity_wall_vertices()
    {
      velocity_wall_vertex.assign(triangulation.n_vertices(), false);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (!cell->is_artificial())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() <
                  boundary_conditions.n_boundary_ids() &&
                boundary_conditions.imposes_velocity(
                  cell->face(f)->boundary_id()))
              for (const auto v : cell->face(f)->vertex_indices())
                velocity_wall_vertex[cell->face(f)->vertex_index(v)] = true;
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::is_free_contact_cell(
      const CellAccessor<dim, dim> &cell) const
    {
      if (!frees_contact_cells())
        return false;
      for (const auto v : cell.vertex_indices())
        if (cell.vertex_index(v) < velocity_wall_vertex.size() &&
            velocity_wall_vertex[cell.vertex_index(v)])
          return true;
      return solid_field->n_solids_near(cell, cell.minimum_vertex_distance()) >=
             2;
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::frees_contact_cells() const
    {
      using F = FluidParameters::FreeContactCells;
      return solid_field != nullptr &&
             (fluid_parameters.free_contact_cells == F::yes ||
              (fluid_parameters.free_contact_cells == F::automatic &&
               moving_solids && !last_was_steady));
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::freed_solid_fraction() const
    {
      // Most scenes free nothing: no pass over the mesh for them.
      if (!frees_contact_cells())
        return 0.;
      const QGauss<dim>           quadrature(fe.degree + 1);
      FEValues<dim>               fe_values(fe,
                              quadrature,
                              update_quadrature_points | update_JxW_values);
      std::vector<double>         vf;
      std::vector<Tensor<1, dim>> u_s;
      std::vector<int>            grain;
      double                      solid = 0, freed = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            solid_field->evaluate(
              *cell, fe_values.get_quadrature_points(), vf, u_s, grain);
            double cell_solid = 0;
            for (const auto q : fe_values.quadrature_point_indices())
              cell_solid += (1. - vf[q]) * fe_values.JxW(q);
            solid += cell_solid;
            if (cell_solid > 0 && is_free_contact_cell(*cell))
              freed += cell_solid;
          }
      solid = Utilities::MPI::sum(solid, mpi_communicator);
      freed = Utilities::MPI::sum(freed, mpi_communicator);
      return solid > 0 ? freed / solid : 0.;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::evaluate_solids(
      const CellAccessor<dim, dim> &cell,
      const std::vector<Point<dim>>  &points,
      std::vector<double>            &void_fraction,
      std::vector<Tensor<1, dim>>    &solid_velocity,
      std::vector<int>               &solid_index) const
    {
      solid_field->evaluate(
        cell, points, void_fraction, solid_velocity, solid_index);
      if (std::any_of(solid_index.begin(),
                      solid_index.end(),
                      [](const int g) { return g >= 0; }) &&
          is_free_contact_cell(cell))
        {
          void_fraction.assign(points.size(), 1.);
          solid_velocity.assign(points.size(), Tensor<1, dim>());
          solid_index.assign(points.size(), -1);
        }
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::make_constraints(const bool with_solids)
    {
      const IndexSet relevant =
        DoFTools::extract_locally_relevant_dofs(dof_handler);
      constraints.clear();
      constraints.reinit(relevant);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      boundary_conditions.make_velocity_constraints(dof_handler,
                                                    constraints,
                                                    time);
      make_pressure_region_constraints(dof_handler,
                                       boundary_conditions.inlet_region(),
                                       boundary_conditions.perimeter_region(),
                                       constraints);
      rigid_dof_grain.clear();
      rigid_dof_shares.clear();
      limit_target.clear();
      hanging_rigid_parents.clear();
      if (with_solids &&
          (rigid_nodes() || constrained_interiors() || penalization_limit()))
        {
          if (penalization_limit())
            add_penalization_limit_constraints();
          else
            add_solid_constraints(dof_handler,
                                  constraints,
                                  rigid_nodes() ? rigid_node_inflation() : 0.,
                                  &rigid_dof_grain);

          // Hanging nodes whose parents are rigid carry part of the grain's
          // reaction; close() below resolves those parents away, so keep
          // the original weights.
          for (const auto &line : constraints.get_lines())
            for (const auto &[parent, weight] : line.entries)
              if (rigid_dof_grain.count(parent))
                hanging_rigid_parents[line.index].emplace_back(parent, weight);

          // Smoothed (assemble()): every pressure node is determined.
          if (!smooth_solid_pressure())
            pin_undetermined_solid_pressures();
        }
      constraints.close();
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::pin_undetermined_solid_pressures()
    {
      // Only locally active dofs: their cells are all owned or ghost.
      // Pinning them spares FGMRES one null vector per node.
      const IndexSet active = DoFTools::extract_locally_active_dofs(dof_handler);
      std::set<types::global_dof_index> free_pressure, solid_pressure;
      std::vector<types::global_dof_index> dof_indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(dof_indices);
            bool solid_cell = true;
            for (unsigned int k = 0; k < dof_indices.size() && solid_cell; ++k)
              if (fe.system_to_component_index(k).first < dim)
                solid_cell = is_fixed_velocity(dof_indices[k]);
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              if (fe.system_to_component_index(k).first == dim)
                (solid_cell ? solid_pressure : free_pressure)
                  .insert(dof_indices[k]);
          }
      for (const auto i : solid_pressure)
        if (free_pressure.count(i) == 0 && active.is_element(i) &&
            !constraints.is_constrained(i))
          constraints.add_line(i);
    }


    template <int dim>
    bool
    PenalizedNavierStokes<dim>::is_fixed_velocity(
      const types::global_dof_index i) const
    {
      if (rigid_dof_grain.count(i))
        return true;
      const auto *entries = constraints.get_constraint_entries(i);
      if (entries == nullptr)
        return false;
      // close() resolves constrained parents away: a hanging node on
      // rigid parents only is then an empty line. Before, compare counts.
      if (entries->empty() || constraints.is_closed())
        return entries->empty();
      const auto hanging = hanging_rigid_parents.find(i);
      return hanging != hanging_rigid_parents.end() &&
             hanging->second.size() == entries->size();
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::add_penalization_limit_constraints()
    {
      // The Theta -> infinity limit of rho* (u^{n+1} - u~) / dt with
      // u~ = vf u^n + (1 - vf) u_s is u^{n+1} = u~ (BDF1, the paper's
      // update), taken per node with one blended u_s (penalization_limit.h);
      // its fixed point, in steady solves, is u = u_s. setup_dofs() asks
      // before the solutions have the new mesh's layout: only which DoFs
      // are fixed matters there.
      const bool transient =
        !last_was_steady && old_solution.size() == dof_handler.n_dofs();
      const auto nodes = penalization_limit_nodes<dim>(
        dof_handler,
        [this](const CellAccessor<dim, dim>  &cell,
               const std::vector<Point<dim>> &points,
               std::vector<double>           &vf,
               std::vector<Tensor<1, dim>>   &u_s,
               std::vector<int>              &grain) {
          solid_field->evaluate(cell, points, vf, u_s, grain);
        },
        [this](const CellAccessor<dim, dim> &cell) {
          return is_free_contact_cell(cell);
        });
      // Boundary, hanging-node and pressure-region constraints keep
      // priority.
      for (const auto &[i, node] : nodes)
        if (!constraints.is_constrained(i) && constraints.can_store_line(i))
          {
            const double old_velocity = transient ? old_solution(i) : 0.;
            const double value =
              transient ? node.void_fraction * old_velocity +
                            (1. - node.void_fraction) * node.target :
                          node.target;
            constraints.add_line(i);
            constraints.set_inhomogeneity(i, value);
            rigid_dof_grain[i] = node.grain_shares.front().first;
            limit_target[i]    = node.target;
            if (node.grain_shares.size() > 1)
              rigid_dof_shares[i] = node.grain_shares;
          }
    }


    template <int dim>
    double
    PenalizedNavierStokes<dim>::rigid_node_inflation() const
    {
      // One offset for the whole mesh (grain surfaces sit in the finest
      // cells): a per-cell spacing would let a coarse neighbour claim nodes
      // that the fine cells sharing them leave free. Q2 nodes are half a
      // cell edge apart.
      double finest = std::numeric_limits<double>::max();
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          finest = std::min(finest, cell->minimum_vertex_distance());
      finest = Utilities::MPI::min(finest, mpi_communicator);
      return fluid_parameters.rigid_node_offset * finest / fe.degree;
    }


    template <int dim>
    void
    PenalizedNavierStokes<dim>::add_solid_constraints(
      const DoFHandler<dim>                  &dof,
      AffineConstraints<double>              &constraints,
      const double                            inflation,
      std::unordered_map<types::global_dof_index, int> *grain_of_dof) const
    {
      // Theta -> infinity: nodes inside a grain move with it (rigid nodes:
      // every node inside; penalization: the nodes of cells wholly inside
      // one grain, so that the penalty stays in cut cells). Boundary and
      // hanging-node constraints keep priority. Ghost cells are visited too,
      // so that ranks agree on shared dofs.
      const FiniteElement<dim> &element = dof.get_fe();
      const Quadrature<dim>     nodes(element.get_unit_support_points());
      FEValues<dim> fe_values(element, nodes, update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices(
        element.n_dofs_per_cell());
      std::vector<double>         vf;
      std::vector<Tensor<1, dim>> u_s;
      std::vector<int>            grain;
      // Nodes of contact cells stay free (is_free_contact_cell()).
      std::set<types::global_dof_index> contact_dofs;
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial() && is_free_contact_cell(*cell))
          {
            cell->get_dof_indices(dof_indices);
            contact_dofs.insert(dof_indices.begin(), dof_indices.end());
          }
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial())
          {
            fe_values.reinit(cell);
            solid_field->evaluate_exact(*cell,
                                        fe_values.get_quadrature_points(),
                                        vf,
                                        u_s,
                                        grain,
                                        inflation);
            cell->get_dof_indices(dof_indices);
            // A box whose nodes all lie in one sphere lies in it.
            if (!rigid_nodes() &&
                !std::all_of(grain.begin(), grain.end(), [&](const int g) {
                  return g >= 0 && g == grain[0];
                }))
              continue;
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              {
                const unsigned int c =
                  element.system_to_component_index(k).first;
                const auto i = dof_indices[k];
                if (c >= dim || grain[k] < 0 || constraints.is_constrained(i) ||
                    !constraints.can_store_line(i) || contact_dofs.count(i))
                  continue;
                constraints.add_line(i);
                if (grain_of_dof != nullptr)
                  {
                    constraints.set_inhomogeneity(i, u_s[k][c]);
                    (*grain_of_dof)[i] = grain[k];
                  }
              }
          }
    }


    template <int dim>
    IndexSet
    PenalizedNavierStokes<dim>::owned_constrained_dofs() const
    {
      IndexSet constrained(dof_handler.n_dofs());
      for (const auto i : dof_handler.locally_owned_dofs())
        if (constraints.is_constrained(i))
          constrained.add_index(i);
      constrained.compress();
      return constrained;
    }


    template <int dim>
    IndexSet
    PenalizedNavierStokes<dim>::constrained_velocity_dofs() const
    {
      // The velocity block comes first in the DoF numbering.
      return owned_constrained_dofs().get_view(0, owned_partitioning[0].size());
    }


    // Instantiated member by member: the class's other members are
    // defined in penalized_navier_stokes.cc and its sibling files.
    template void
    PenalizedNavierStokes<2>::set_solid_field(const SolidField<2> *solids);
    template void
    PenalizedNavierStokes<2>::set_moving_solids(const bool moving);
    template void
    PenalizedNavierStokes<2>::find_velocity_wall_vertices();
    template bool
    PenalizedNavierStokes<2>::is_free_contact_cell(
      const CellAccessor<2, 2> &cell) const;
    template bool
    PenalizedNavierStokes<2>::frees_contact_cells() const;
    template double
    PenalizedNavierStokes<2>::freed_solid_fraction() const;
    template void
    PenalizedNavierStokes<2>::evaluate_solids(
      const CellAccessor<2, 2>    &cell,
      const std::vector<Point<2>> &points,
      std::vector<double>         &void_fraction,
      std::vector<Tensor<1, 2>>   &solid_velocity,
      std::vector<int>            &solid_index) const;
    template void
    PenalizedNavierStokes<2>::make_constraints(const bool with_solids);
    template void
    PenalizedNavierStokes<2>::pin_undetermined_solid_pressures();
    template bool
    PenalizedNavierStokes<2>::is_fixed_velocity(
      const types::global_dof_index i) const;
    template void
    PenalizedNavierStokes<2>::add_penalization_limit_constraints();
    template double
    PenalizedNavierStokes<2>::rigid_node_inflation() const;
    template void
    PenalizedNavierStokes<2>::add_solid_constraints(
      const DoFHandler<2>                              &dof,
      AffineConstraints<double>                        &constraints,
      const double                                      inflation,
      std::unordered_map<types::global_dof_index, int> *grain_of_dof) const;
    template IndexSet
    PenalizedNavierStokes<2>::owned_constrained_dofs() const;
    template IndexSet
    PenalizedNavierStokes<2>::constrained_velocity_dofs() const;
    template void
    PenalizedNavierStokes<3>::set_solid_field(const SolidField<3> *solids);
    template void
    PenalizedNavierStokes<3>::set_moving_solids(const bool moving);
    template void
    PenalizedNavierStokes<3>::find_velocity_wall_vertices();
    template bool
    PenalizedNavierStokes<3>::is_free_contact_cell(
      const CellAccessor<3, 3> &cell) const;
    template bool
    PenalizedNavierStokes<3>::frees_contact_cells() const;
    template double
    PenalizedNavierStokes<3>::freed_solid_fraction() const;
    template void
    PenalizedNavierStokes<3>::evaluate_solids(
      const CellAccessor<3, 3>    &cell,
      const std::vector<Point<3>> &points,
      std::vector<double>         &void_fraction,
      std::vector<Tensor<1, 3>>   &solid_velocity,
      std::vector<int>            &solid_index) const;
    template void
    PenalizedNavierStokes<3>::make_constraints(const bool with_solids);
    template void
    PenalizedNavierStokes<3>::pin_undetermined_solid_pressures();
    template bool
    PenalizedNavierStokes<3>::is_fixed_velocity(
      const types::global_dof_index i) const;
    template void
    PenalizedNavierStokes<3>::add_penalization_limit_constraints();
    template double
    PenalizedNavierStokes<3>::rigid_node_inflation() const;
    template void
    PenalizedNavierStokes<3>::add_solid_constraints(
      const DoFHandler<3>                              &dof,
      AffineConstraints<double>                        &constraints,
      const double                                      inflation,
      std::unordered_map<types::global_dof_index, int> *grain_of_dof) const;
    template IndexSet
    PenalizedNavierStokes<3>::owned_constrained_dofs() const;
    template IndexSet
    PenalizedNavierStokes<3>::constrained_velocity_dofs() const;
  } // namespace fluid
} // namespace softsand
