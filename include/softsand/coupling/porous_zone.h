#ifndef softsand_coupling_porous_zone_h
#define softsand_coupling_porous_zone_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>

#include <softsand/coupling/grain_locator.h>
#include <softsand/fluid/solid_field.h>

#include <vector>

namespace softsand
{
  namespace coupling
  {
    /**
     * The hybrid model (doc/architecture.md, "The hybrid model"): grains are
     * resolved within `resolved radius` of the inlet's axis; beyond it the
     * fluid cells see them as a porous medium whose permeability follows
     * Ergun's closure of the local porosity,
     *
     *   -grad p = mu A (1 - phi)^2 / (phi^3 d^2) u
     *             + rho B (1 - phi) / (phi^3 d) |u| u,
     *
     * with A = `kozeny constant` (calibrated against the resolved model on
     * the same pack) and B = `ergun inertial constant`; the pore fluid's
     * inertia is rho alpha / phi per unit superficial momentum, with
     * Berryman's tortuosity alpha = 1 + r (1 / phi - 1), r =
     * `tortuosity constant` (1/2 for spheres).
     */
    struct HybridModelParameters
    {
      bool   enabled           = false;
      double resolved_radius   = 0;
      double kozeny_constant   = 180;
      double inertial_constant = 1.75;
      double averaging_width   = 1;
      double tortuosity_constant = 0.5;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };


    /**
     * Which cells and grains are porous, and each porous cell's porosity and
     * drag coefficients. The porosity of a cell is the grains' volume in its
     * box grown by `averaging width` mean diameters (clipped to the
     * domain), each grain's share by the product of its slab fractions along
     * the axes (exact for a slab, a few per cent off at a box's corners).
     */
    template <int dim>
    class PorousZone
    {
    public:
      PorousZone(const std::vector<dem::Grain<dim>> &grains,
                 const GrainLocator<dim>            &locator,
                 const HybridModelParameters        &parameters,
                 const Point<dim>                   &axis_point,
                 const Tensor<1, dim>               &axis,
                 const BoundingBox<dim>             &domain);

      /// Whether @p x lies within the resolved radius of the axis.
      bool
      resolved(const Point<dim> &x) const
      {
        return distance_from_axis(x) < parameters.resolved_radius;
      }

      /// Cells whose centre lies outside the resolved zone.
      bool
      is_porous(const CellAccessor<dim, dim> &cell) const
      {
        return !resolved(cell.center());
      }

      /// The drag coefficients of @p cell if it is porous (else none).
      fluid::PorousCell<dim>
      porous_cell(const CellAccessor<dim, dim> &cell) const
      {
        return is_porous(cell) ? coefficients(cell) : fluid::PorousCell<dim>();
      }

      /// The porous coefficients of @p cell's neighbourhood, whether the
      /// cell is porous or not (a grain's porous share may be evaluated in
      /// a resolved cell at the zone's edge).
      fluid::PorousCell<dim>
      coefficients(const CellAccessor<dim, dim> &cell) const;

      /// The share of grain @p g's volume beyond the resolved radius (the
      /// grain's surface cut by the tangent plane of the zone's cylinder):
      /// its fluid force comes from the porous model by this share and
      /// from its rigid nodes for the rest.
      double
      porous_share(const dem::Grain<dim> &g) const;

      /// Grains that reach into the resolved zone: the mesh is refined
      /// around these only.
      std::vector<dem::Grain<dim>>
      resolved_grains() const;

      /// Porosities below this are taken at it (Ergun's closure diverges
      /// as phi -> 0; overlapping grains can fill an averaging box).
      static constexpr double min_porosity = 0.05;

      /// The part of x - (a point on the axis) normal to the axis.
      Tensor<1, dim>
      radial_vector(const Point<dim> &x) const
      {
        Tensor<1, dim> r = x - axis_point;
        if (dim == 3)
          r -= (r * axis) * axis;
        return r;
      }

      double
      distance_from_axis(const Point<dim> &x) const
      {
        return radial_vector(x).norm();
      }

      double
      resolved_radius() const
      {
        return parameters.resolved_radius;
      }

    private:
      const std::vector<dem::Grain<dim>> &grains;
      const GrainLocator<dim>            &locator;
      HybridModelParameters               parameters;
      Point<dim>                          axis_point;
      Tensor<1, dim>                      axis;
      BoundingBox<dim>                    domain;
      double                              mean_diameter;
    };
  } // namespace coupling
} // namespace softsand

#endif
