#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/trilinos_vector.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/fluid/pressure_region.h>

#include <map>
#include <set>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    void
    PressureRegion<dim>::declare_parameters(ParameterHandler  &prm,
                                            const std::string &name,
                                            const Side         side)
    {
      const std::string where =
        side == Side::inside ? "inside" : "outside";
      prm.enter_subsection(name);
      prm.declare_entry(
        "type",
        "none",
        Patterns::Selection("none|cylinder"),
        "none: no such region; cylinder: the fluid " + where +
          " a cylinder (2D: a circle) is a reservoir at the given pressure "
          "(pressure nodes fixed, no viscous resistance: the rest of the "
          "fluid sees a pressure condition on the region's surface, made of "
          "the faces of the cells whose centre lies " +
          where + " the cylinder).");
      base::declare_double_list(prm,
                                "center",
                                dim == 2 ? "0, 0" : "0, 0, 0",
                                "A point on the cylinder's axis (2D: the "
                                "circle's centre) (m).");
      base::declare_double_list(prm,
                                "axis",
                                dim == 2 ? "0, 0" : "0, 0, 1",
                                "Direction of the cylinder's axis (3D; "
                                "normalized; ignored in 2D).");
      prm.declare_entry("radius",
                        "0",
                        Patterns::Double(0),
                        "Radius of the cylinder (m).");
      prm.declare_entry("pressure",
                        "0",
                        Patterns::Double(),
                        "Pressure of the reservoir (Pa).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    PressureRegion<dim>::parse_parameters(ParameterHandler  &prm,
                                          const std::string &name,
                                          const Side         which_side,
                                          const std::string &path)
    {
      prm.enter_subsection(name);
      side       = which_side;
      is_enabled = prm.get("type") == "cylinder";
      center     = base::get_point<dim>(prm, "center");
      axis       = base::get_tensor<dim>(prm, "axis");
      radius     = prm.get_double("radius");
      pressure   = prm.get_double("pressure");
      if (is_enabled)
        {
          if (!(radius > 0))
            base::throw_invalid_parameter(path + "/radius",
                                          prm.get("radius"),
                                          "a cylinder region needs a radius "
                                          "> 0 m");
          if (dim == 3)
            {
              if (!(axis.norm() > 0))
                base::throw_invalid_parameter(path + "/axis",
                                              prm.get("axis"),
                                              "the axis must be a nonzero "
                                              "vector");
              axis /= axis.norm();
            }
        }
      prm.leave_subsection();
    }

    template <int dim>
    void
    make_pressure_region_constraints(const DoFHandler<dim>     &dof_handler,
                                     const PressureRegion<dim> &inlet,
                                     const PressureRegion<dim> &perimeter,
                                     AffineConstraints<double> &constraints)
    {
      if (!inlet.enabled() && !perimeter.enabled())
        return;
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      // The owner of a DoF decides (its cells are all owned or ghost there)
      // and the other ranks that see it take the owner's word: a rank that
      // knows a DoF only from a ghost cell, e.g. the coarse parent of its
      // own hanging nodes, cannot tell whether a cell it does not see
      // shares it, and constraints that differ between ranks gave
      // velocities of 1e5 m/s in the inlet (test inlet_hanging_nodes).
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      const IndexSet  relevant =
        DoFTools::extract_locally_relevant_dofs(dof_handler);
      std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
      std::map<types::global_dof_index, double> region_pressure;
      std::set<types::global_dof_index>         region_velocity;
      const auto region_of = [&](const Point<dim> &x) {
        return inlet.contains(x)     ? &inlet :
               perimeter.contains(x) ? &perimeter :
                                       nullptr;
      };
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          if (const auto *region = region_of(cell->center()))
            {
              cell->get_dof_indices(dof_indices);
              for (unsigned int k = 0; k < dof_indices.size(); ++k)
                if (fe.system_to_component_index(k).first == dim)
                  region_pressure.emplace(dof_indices[k], region->pressure);
                else
                  region_velocity.insert(dof_indices[k]);
            }
      // Velocity nodes that a fluid cell shares carry the traction
      // condition; the others are not part of the flow.
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && region_of(cell->center()) == nullptr)
          {
            cell->get_dof_indices(dof_indices);
            for (const auto i : dof_indices)
              region_velocity.erase(i);
          }

      // What the owner fixed: 1 a velocity, 2 a pressure (whose value
      // travels in a second vector). One DoF is either, never both.
      const MPI_Comm comm = dof_handler.get_communicator();
      TrilinosWrappers::MPI::Vector fixed(owned, comm), value(owned, comm);
      for (const auto &[i, p] : region_pressure)
        if (owned.is_element(i))
          {
            fixed[i] = 2;
            value[i] = p;
          }
      for (const auto i : region_velocity)
        if (owned.is_element(i))
          fixed[i] = 1;
      fixed.compress(VectorOperation::insert);
      value.compress(VectorOperation::insert);
      TrilinosWrappers::MPI::Vector seen_fixed(owned, relevant, comm),
        seen_value(owned, relevant, comm);
      seen_fixed = fixed;
      seen_value = value;

      for (const auto i : relevant)
        if (!constraints.is_constrained(i) && constraints.can_store_line(i))
          {
            if (seen_fixed(i) > 1.5)
              {
                constraints.add_line(i);
                constraints.set_inhomogeneity(i, seen_value(i));
              }
            else if (seen_fixed(i) > 0.5)
              constraints.add_line(i);
          }
    }

    template class PressureRegion<2>;
    template class PressureRegion<3>;
    template void
    make_pressure_region_constraints(const DoFHandler<2> &,
                                     const PressureRegion<2> &,
                                     const PressureRegion<2> &,
                                     AffineConstraints<double> &);
    template void
    make_pressure_region_constraints(const DoFHandler<3> &,
                                     const PressureRegion<3> &,
                                     const PressureRegion<3> &,
                                     AffineConstraints<double> &);
  } // namespace fluid
} // namespace softsand
