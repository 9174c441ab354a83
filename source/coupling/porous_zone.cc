#include <softsand/base/parameter_tools.h>
#include <softsand/coupling/porous_zone.h>

#include <algorithm>
#include <cmath>

namespace softsand
{
  namespace coupling
  {
    void
    HybridModelParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      prm.enter_subsection("hybrid model");
      prm.declare_entry(
        "resolved radius",
        "none",
        Patterns::Anything(),
        "none: every grain is resolved. A distance (m, >= 0) from the axis "
        "of the inlet region: grains are resolved within it; beyond it the "
        "fluid sees them as a porous medium (Ergun's closure of the local "
        "porosity) on cells not refined around grains, and their fluid "
        "force is -V (grad p - phi c (u - phi u_s) / (1 - phi)) at their "
        "centre. 0: no grain resolved.");
      prm.declare_entry("kozeny constant",
                        "180",
                        Patterns::Double(0),
                        "A in the permeability K = phi^3 d^2 / (A (1 - "
                        "phi)^2) of the porous cells (180: Kozeny-Carman; "
                        "calibrate it against the resolved model on the "
                        "same pack and mesh, doc/hybrid_model.md).");
      prm.declare_entry("ergun inertial constant",
                        "1.75",
                        Patterns::Double(0),
                        "B in Forchheimer's term rho B (1 - phi) / (phi^3 d) "
                        "|u| u of the porous cells (1.75: Ergun).");
      prm.declare_entry("averaging width",
                        "1",
                        Patterns::Double(0),
                        "How far (in mean grain diameters) a porous cell's "
                        "box is grown on each side to average the porosity. "
                        "Porosities below 0.05 are taken at 0.05.");
      prm.declare_entry("tortuosity constant",
                        "0.5",
                        Patterns::Double(0),
                        "r in the porous cells' tortuosity alpha = 1 + r (1 / "
                        "phi - 1), which raises the pore fluid's inertia to "
                        "rho alpha / phi per unit superficial momentum "
                        "(Berryman: 1/2 for spheres; 0: no tortuosity).");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    void
    HybridModelParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("coupling");
      prm.enter_subsection("hybrid model");
      const std::string radius = prm.get("resolved radius");
      enabled                  = radius != "none";
      if (enabled)
        {
          try
            {
              std::size_t end = 0;
              resolved_radius = std::stod(radius, &end);
              if (end != radius.size())
                throw std::invalid_argument(radius);
            }
          catch (const std::exception &)
            {
              resolved_radius = -1;
            }
          if (!(resolved_radius >= 0) || !std::isfinite(resolved_radius))
            base::throw_invalid_parameter(
              "coupling/hybrid model/resolved radius",
              radius,
              "none, or a distance in m >= 0 from the inlet region's axis");
        }
      kozeny_constant = prm.get_double("kozeny constant");
      if (!(kozeny_constant > 0))
        base::throw_invalid_parameter("coupling/hybrid model/kozeny constant",
                                      prm.get("kozeny constant"),
                                      "a number > 0");
      inertial_constant   = prm.get_double("ergun inertial constant");
      tortuosity_constant = prm.get_double("tortuosity constant");
      averaging_width     = prm.get_double("averaging width");
      if (!(averaging_width > 0))
        base::throw_invalid_parameter("coupling/hybrid model/averaging width",
                                      prm.get("averaging width"),
                                      "a number of mean diameters > 0");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    namespace
    {
      /// The fraction of a sphere's (2D: disc's) volume on the side
      /// x < t r of a plane through its axis, t in [-1, 1].
      template <int dim>
      double
      fraction_below(const double t)
      {
        if (t <= -1)
          return 0.;
        if (t >= 1)
          return 1.;
        if (dim == 3)
          return (1 + t) * (1 + t) * (2 - t) / 4;
        return 0.5 + (t * std::sqrt(1 - t * t) + std::asin(t)) / M_PI;
      }
    } // namespace


    template <int dim>
    PorousZone<dim>::PorousZone(const std::vector<dem::Grain<dim>> &grains,
                                const GrainLocator<dim>            &locator,
                                const HybridModelParameters &parameters,
                                const Point<dim>            &axis_point,
                                const Tensor<1, dim>        &axis,
                                const BoundingBox<dim>      &domain)
      : grains(grains)
      , locator(locator)
      , parameters(parameters)
      , axis_point(axis_point)
      , axis(axis.norm() > 0 ? axis / axis.norm() : axis)
      , domain(domain)
      , mean_diameter(dem::mean_diameter(grains))
    {}


    template <int dim>
    fluid::PorousCell<dim>
    PorousZone<dim>::coefficients(const CellAccessor<dim, dim> &cell) const
    {
      fluid::PorousCell<dim> result;
      result.porous = true;

      BoundingBox<dim> box = cell.bounding_box();
      box.extend(parameters.averaging_width * mean_diameter);
      auto lo = box.get_boundary_points().first;
      auto hi = box.get_boundary_points().second;
      double box_volume = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lo[d] = std::max(lo[d], domain.get_boundary_points().first[d]);
          hi[d] = std::min(hi[d], domain.get_boundary_points().second[d]);
          box_volume *= std::max(0., hi[d] - lo[d]);
        }
      if (box_volume <= 0)
        return result;

      thread_local std::vector<unsigned int> near;
      near.clear();
      locator.grains_near_box(BoundingBox<dim>(std::make_pair(lo, hi)), near);
      double         solid = 0, d3 = 0, d2 = 0;
      Tensor<1, dim> momentum;
      for (const unsigned int k : near)
        {
          const auto &g     = grains[k];
          double      share = 1;
          for (unsigned int d = 0; d < dim && share > 0; ++d)
            share *= fraction_below<dim>((hi[d] - g.center[d]) / g.radius) -
                     fraction_below<dim>((lo[d] - g.center[d]) / g.radius);
          if (share <= 0)
            continue;
          const double v = share * g.measure();
          solid += v;
          momentum += v * g.velocity;
          d3 += share * std::pow(g.diameter(), 3);
          d2 += share * g.diameter() * g.diameter();
        }
      if (solid <= 0)
        return result;
      const double phi =
        std::max(min_porosity, 1. - std::min(1., solid / box_volume));
      const double d   = d3 / d2; // Sauter mean diameter
      result.porosity  = phi;
      result.inverse_permeability =
        parameters.kozeny_constant * (1 - phi) * (1 - phi) /
        (phi * phi * phi * d * d);
      result.inertial_coefficient =
        parameters.inertial_constant * (1 - phi) / (phi * phi * phi * d);
      result.solid_velocity = momentum / solid;
      result.inertia_scale =
        (1. + parameters.tortuosity_constant * (1. / phi - 1.)) / phi;
      return result;
    }


    template <int dim>
    double
    PorousZone<dim>::porous_share(const dem::Grain<dim> &g) const
    {
      // Signed distance of the centre beyond the zone's surface.
      const double s = distance_from_axis(g.center) - parameters.resolved_radius;
      return 1. - fraction_below<dim>(-s / g.radius);
    }


    template <int dim>
    std::vector<dem::Grain<dim>>
    PorousZone<dim>::resolved_grains() const
    {
      std::vector<dem::Grain<dim>> inside;
      for (const auto &g : grains)
        if (distance_from_axis(g.center) - g.radius <
            parameters.resolved_radius)
          inside.push_back(g);
      return inside;
    }


    template class PorousZone<2>;
    template class PorousZone<3>;
  } // namespace coupling
} // namespace softsand
