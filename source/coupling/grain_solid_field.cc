#include <softsand/base/parameter_tools.h>
#include <softsand/coupling/grain_solid_field.h>

#include <map>

namespace softsand
{
  namespace coupling
  {
    void
    VoidFractionParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      prm.declare_entry(
        "void fraction model",
        "cell average",
        Patterns::Selection("cell average|cell majority|quadrature point"),
        "cell average: the paper's cell void fraction (covered volume "
        "fraction, sub-sampled); cell majority: a cut cell is solid (vf = 0) "
        "where grains cover at least half of it and fluid otherwise (with a "
        "large theta the cell average makes every cut cell solid, and the Q2 "
        "nodes on their faces put the no-slip surface half a cell outside "
        "the grain on average; the majority rule puts it on the grain); "
        "quadrature point: the exact solid indicator at each quadrature "
        "point. The porosity statistics always use the cell average.");
      prm.declare_entry("cell average subdivisions",
                        "4",
                        Patterns::Integer(1, 16),
                        "Sub-samples per direction and cell for the cell "
                        "average (and for the porosity).");
      prm.leave_subsection();
    }


    void
    VoidFractionParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      const std::string m = prm.get("void fraction model");
      model = m == "cell average"  ? Model::cell_average :
              m == "cell majority" ? Model::cell_majority :
                                     Model::quadrature_point;
      subdivisions = prm.get_integer("cell average subdivisions");
      prm.leave_subsection();
    }


    template <int dim>
    GrainSolidField<dim>::GrainSolidField(
      const std::vector<dem::Grain<dim>> &grains,
      const VoidFractionParameters       &parameters)
      : grains(grains)
      , parameters(parameters)
      , grain_locator(grains)
    {}


    template <int dim>
    void
    GrainSolidField<dim>::set_porous_zone(
      const HybridModelParameters &hybrid,
      const Point<dim>            &axis_point,
      const Tensor<1, dim>        &axis,
      const BoundingBox<dim>      &domain)
    {
      zone = std::make_unique<PorousZone<dim>>(
        grains, grain_locator, hybrid, axis_point, axis, domain);
      resolved_grains  = zone->resolved_grains();
      resolved_locator = std::make_unique<GrainLocator<dim>>(resolved_grains);
    }


    template <int dim>
    double
    GrainSolidField<dim>::cell_solid_fraction(
      const CellAccessor<dim, dim> &cell,
      int                                                    &dominant) const
    {
      const BoundingBox<dim> box = cell.bounding_box();
      // The grains near the cell, searched once for all its samples.
      thread_local std::vector<unsigned int> near;
      const auto relation = grain_locator.classify_box(box, dominant, near);
      if (relation == GrainLocator<dim>::BoxRelation::outside_all)
        return 0;
      if (relation == GrainLocator<dim>::BoxRelation::inside_one)
        return 1;

      // Cut cell: midpoint sub-sampling of the box (cells are axis-aligned).
      const unsigned int n  = parameters.subdivisions;
      const auto        &lo = box.get_boundary_points().first;
      const auto        &hi = box.get_boundary_points().second;
      std::map<int, unsigned int> count;
      unsigned int                covered = 0, total = 0;
      std::array<unsigned int, dim> i{};
      while (true)
        {
          Point<dim> x;
          for (unsigned int d = 0; d < dim; ++d)
            x[d] = lo[d] + (i[d] + 0.5) / n * (hi[d] - lo[d]);
          const int g = grain_locator.containing_grain(x, 0., near);
          if (g >= 0)
            {
              ++covered;
              ++count[g];
            }
          ++total;
          unsigned int d = 0;
          for (; d < dim; ++d)
            {
              if (++i[d] < n)
                break;
              i[d] = 0;
            }
          if (d == dim)
            break;
        }
      dominant           = -1;
      unsigned int most  = 0;
      for (const auto &[g, c] : count)
        if (c > most)
          {
            most     = c;
            dominant = g;
          }
      // A cut cell whose samples all miss still touches a grain: report it so
      // that the grain velocity is defined there.
      if (dominant < 0)
        {
          double best = std::numeric_limits<double>::max();
          for (const unsigned int k : near)
            {
              const double s =
                box.center().distance(grains[k].center) - grains[k].radius;
              if (s < best)
                {
                  best     = s;
                  dominant = k;
                }
            }
        }
      return double(covered) / total;
    }


    template <int dim>
    void
    GrainSolidField<dim>::evaluate(
      const CellAccessor<dim, dim> &cell,
      const std::vector<Point<dim>>                           &points,
      std::vector<double>                                     &void_fraction,
      std::vector<Tensor<1, dim>>                             &solid_velocity,
      std::vector<int>                                        &solid_index) const
    {
      const unsigned int n_q = points.size();
      void_fraction.assign(n_q, 1.);
      solid_velocity.assign(n_q, Tensor<1, dim>());
      solid_index.assign(n_q, -1);
      if (in_porous_zone(cell))
        return;

      int        dominant = -1;
      const auto relation =
        grain_locator.classify_box(cell.bounding_box(), dominant);
      if (relation == GrainLocator<dim>::BoxRelation::outside_all)
        return;
      if (relation == GrainLocator<dim>::BoxRelation::inside_one)
        {
          for (unsigned int q = 0; q < n_q; ++q)
            {
              void_fraction[q]  = 0;
              solid_index[q]    = dominant;
              solid_velocity[q] = grains[dominant].rigid_velocity(points[q]);
            }
          return;
        }

      if (parameters.model == VoidFractionParameters::Model::quadrature_point)
        evaluate_exact(cell, points, void_fraction, solid_velocity, solid_index);
      else
        {
          double solid = cell_solid_fraction(cell, dominant);
          if (parameters.model == VoidFractionParameters::Model::cell_majority)
            solid = (solid >= 0.5 ? 1. : 0.);
          if (solid == 0 || dominant < 0)
            return;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              void_fraction[q] = 1. - solid;
              // The grain under the point if any, else the cell's main grain.
              const int g      = grain_locator.containing_grain(points[q]);
              solid_index[q]   = (g >= 0 ? g : dominant);
              solid_velocity[q] =
                grains[solid_index[q]].rigid_velocity(points[q]);
            }
        }
    }

    template <int dim>
    void
    GrainSolidField<dim>::evaluate_exact(
      const CellAccessor<dim, dim> &cell,
      const std::vector<Point<dim>>  &points,
      std::vector<double>            &void_fraction,
      std::vector<Tensor<1, dim>>    &solid_velocity,
      std::vector<int>               &solid_index,
      const double                    inflation) const
    {
      const unsigned int n_q = points.size();
      void_fraction.assign(n_q, 1.);
      solid_velocity.assign(n_q, Tensor<1, dim>());
      solid_index.assign(n_q, -1);
      if (in_porous_zone(cell))
        return;
      int              dominant = -1;
      BoundingBox<dim> box      = cell.bounding_box();
      if (inflation > 0)
        box.extend(inflation);
      // The grains near the cell, searched once: the points lie in it.
      thread_local std::vector<unsigned int> near;
      if (grain_locator.classify_box(box, dominant, near) ==
          GrainLocator<dim>::BoxRelation::outside_all)
        return;
      for (unsigned int q = 0; q < n_q; ++q)
        {
          // An FESystem lists each support point once per component, one
          // after the other.
          if (q > 0 && points[q] == points[q - 1])
            {
              void_fraction[q]  = void_fraction[q - 1];
              solid_index[q]    = solid_index[q - 1];
              solid_velocity[q] = solid_velocity[q - 1];
              continue;
            }
          const int g =
            grain_locator.containing_grain(points[q], inflation, near);
          if (g >= 0)
            {
              void_fraction[q]  = 0;
              solid_index[q]    = g;
              solid_velocity[q] = grains[g].rigid_velocity(points[q]);
            }
        }
    }


    template <int dim>
    unsigned int
    GrainSolidField<dim>::n_solids_near(const CellAccessor<dim, dim> &cell,
                                        const double reach) const
    {
      if (in_porous_zone(cell))
        return 0;
      BoundingBox<dim> box = cell.bounding_box();
      box.extend(reach);
      std::vector<unsigned int> near;
      grain_locator.grains_near_box(box, near);
      const auto &lo = box.get_boundary_points().first;
      const auto &hi = box.get_boundary_points().second;
      unsigned int n = 0;
      for (const unsigned int k : near)
        {
          // Distance from the centre to the grown box against the radius.
          double distance_squared = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double x = grains[k].center[d];
              const double gap =
                x < lo[d] ? lo[d] - x : (x > hi[d] ? x - hi[d] : 0.);
              distance_squared += gap * gap;
            }
          if (distance_squared < grains[k].radius * grains[k].radius && ++n == 2)
            break;
        }
      return n;
    }


    template class GrainSolidField<2>;
    template class GrainSolidField<3>;
  } // namespace coupling
} // namespace softsand
