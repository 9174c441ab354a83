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
