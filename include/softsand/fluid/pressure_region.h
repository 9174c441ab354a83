#ifndef softsand_fluid_pressure_region_h
#define softsand_fluid_pressure_region_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>

#include <string>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * A fluid reservoir at a given pressure inside (or outside) a cylinder
     * that need not follow the mesh: the central inlet of the radial
     * Hele-Shaw cell, where the injection pressure p_i is imposed, and its
     * constant-pressure perimeter.
     *
     * The region is the union of the cells whose centre lies in it. There
     * the pressure nodes are constrained to the given pressure, the cells
     * assemble only the pressure term -(p, div v) (no viscous, inertial or
     * Brinkman term), and the velocity nodes that no other cell shares are
     * constrained to zero (they would be undetermined). For the rest of the
     * fluid the region's cells then act exactly as a traction condition
     * mu du/dn - p n = -p_region n on the staircase surface of the region,
     * the do-nothing condition of a pressure face: the reservoir supplies
     * or takes fluid without resistance. (Constraining the pressure alone
     * would leave a viscous fluid at rest inside the region that drags the
     * flow leaving it: about 20 % more resistance in a Hele-Shaw cell whose
     * gap is comparable to the inlet radius.)
     */
    template <int dim>
    class PressureRegion
    {
    public:
      enum class Side
      {
        inside,
        outside
      };

      /// Declare the entries of subsection @p name (already entered by the
      /// caller's subsection); @p side says which side of the cylinder the
      /// region is, for the documentation.
      static void
      declare_parameters(ParameterHandler  &prm,
                         const std::string &name,
                         const Side         side);
      /// @p path is the subsection path for error messages.
      void
      parse_parameters(ParameterHandler  &prm,
                       const std::string &name,
                       const Side         side,
                       const std::string &path);

      bool
      enabled() const
      {
        return is_enabled;
      }

      /// Whether the point @p x (a cell centre) lies in the region.
      bool
      contains(const Point<dim> &x) const
      {
        if (!is_enabled)
          return false;
        Tensor<1, dim> r = x - center;
        if (dim == 3)
          r -= (r * axis) * axis;
        const bool in_cylinder = r.norm_square() < radius * radius;
        return side == Side::inside ? in_cylinder : !in_cylinder;
      }

      /// Distance of @p x from the cylinder's axis (m).
      double
      distance_from_axis(const Point<dim> &x) const
      {
        Tensor<1, dim> r = x - center;
        if (dim == 3)
          r -= (r * axis) * axis;
        return r.norm();
      }

      bool           is_enabled = false;
      Side           side       = Side::inside;
      /// A point on the cylinder's axis (2D: the circle's centre) (m).
      Point<dim>     center;
      /// Unit axis of the cylinder (3D; ignored in 2D).
      Tensor<1, dim> axis;
      double         radius   = 0;
      /// Pressure of the reservoir (Pa).
      double         pressure = 0;
    };


    /**
     * Add the constraints of the pressure regions (PressureRegion) for the
     * Taylor-Hood element of @p dof_handler: the pressure nodes of the
     * regions' cells to the region's pressure, their velocity nodes that no
     * other cell shares to zero. Nodes already constrained (boundary
     * conditions, hanging nodes) keep their constraints.
     */
    template <int dim>
    void
    make_pressure_region_constraints(const DoFHandler<dim>     &dof_handler,
                                     const PressureRegion<dim> &inlet,
                                     const PressureRegion<dim> &perimeter,
                                     AffineConstraints<double> &constraints);
  } // namespace fluid
} // namespace softsand

#endif
