#ifndef softsand_fluid_solid_field_h
#define softsand_fluid_solid_field_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_accessor.h>

#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * A cell of the hybrid model's porous zone: its grains are not resolved
     * but seen as a porous medium (doc/architecture.md, "The hybrid model").
     * The momentum equation there carries the drag
     * (mu a + rho b |u - phi u_s|) (u - phi u_s), u the superficial
     * velocity, so that a resting pack gives Darcy's law with K = 1 / a and
     * Forchheimer's correction b; its time derivative is rho alpha / phi
     * du/dt (alpha the tortuosity) and its viscosity mu / phi.
     */
    template <int dim>
    struct PorousCell
    {
      bool           porous               = false;
      double         porosity             = 1;
      double         inverse_permeability = 0; // a [1/m^2]
      double         inertial_coefficient = 0; // b [1/m]
      Tensor<1, dim> solid_velocity;           // the grains' mean velocity
      /// The pore fluid's inertia per unit superficial momentum: the
      /// tortuosity over the porosity, alpha / phi (1 outside).
      double inertia_scale = 1;

      /// The grains' superficial velocity phi u_s: the drag acts on
      /// u - grain_flux().
      Tensor<1, dim>
      grain_flux() const
      {
        return porosity * solid_velocity;
      }

      /// The drag coefficient for the relative superficial velocity
      /// @p relative.
      double
      drag(const double           viscosity,
           const double           density,
           const Tensor<1, dim> &relative) const
      {
        return viscosity * inverse_permeability +
               density * inertial_coefficient * relative.norm();
      }
    };


    /**
     * What the penalized fluid needs to know about the solids: at the
     * quadrature points of a cell, the void fraction vf (1 in fluid, 0 inside
     * a solid) and the rigid velocity u_s of the solid covering the point.
     * The fluid module sees only this interface; coupling/ implements it for
     * grains.
     */
    template <int dim>
    class SolidField
    {
    public:
      virtual ~SolidField() = default;

      /// Whether @p cell lies in a porous zone and, if so, its drag
      /// coefficients. Such cells see no solid through evaluate().
      virtual PorousCell<dim>
      porous_cell(const CellAccessor<dim, dim> &) const
      {
        return {};
      }

      /// Whether any cell may be porous (no pass over cells otherwise).
      virtual bool
      has_porous_zone() const
      {
        return false;
      }

      /// Fill @p void_fraction, @p solid_velocity and @p solid_index (-1:
      /// no solid) for the @p points of @p cell. Cells far from any solid
      /// return quickly with vf = 1.
      virtual void
      evaluate(const CellAccessor<dim, dim> &cell,
               const std::vector<Point<dim>>  &points,
               std::vector<double>            &void_fraction,
               std::vector<Tensor<1, dim>>    &solid_velocity,
               std::vector<int>               &solid_index) const = 0;

      /// As evaluate(), but always with the exact solid indicator (vf = 0
      /// or 1 at each point) of the solids grown by @p inflation (m),
      /// whatever void fraction model the scene uses: the rigid-node model
      /// needs to know which nodes lie inside a solid.
      virtual void
      evaluate_exact(const CellAccessor<dim, dim> &cell,
                     const std::vector<Point<dim>>  &points,
                     std::vector<double>            &void_fraction,
                     std::vector<Tensor<1, dim>>    &solid_velocity,
                     std::vector<int>               &solid_index,
                     const double                    inflation = 0) const = 0;

      /// How many distinct solids come within @p reach (m) of @p cell's
      /// bounding box (counting stops at 2): a cell near two solids sits in
      /// a contact, where their rigid motions may conflict.
      virtual unsigned int
      n_solids_near(const CellAccessor<dim, dim> &cell,
                    const double                  reach) const = 0;
    };
  } // namespace fluid
} // namespace softsand

#endif
