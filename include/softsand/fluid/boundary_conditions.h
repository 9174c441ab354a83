#ifndef softsand_fluid_boundary_conditions_h
#define softsand_fluid_boundary_conditions_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/affine_constraints.h>

#include <softsand/fluid/pressure_region.h>

#include <array>
#include <string>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * Boundary conditions on the faces of the box domain, one subsection per
     * face ("x min" = boundary id 0, "x max" = 1, "y min" = 2, ...). A
     * cylindrical domain keeps the two faces normal to its axis as its ends;
     * its mantle (boundary id 2 dim) is a no-slip wall.
     * Velocity-type conditions become constraints; a pressure face is a
     * natural (do-nothing) condition with prescribed mean normal stress.
     */
    template <int dim>
    class BoundaryConditions
    {
    public:
      enum class Type
      {
        no_slip,
        velocity,
        flow_rate,
        function,
        pressure,
        moving_wall,
        symmetry
      };

      struct Face
      {
        Type           type = Type::no_slip;
        Tensor<1, dim> velocity;
        double         flow_rate = 0;
        std::string    function;
        double         pressure = 0;
      };

      static constexpr unsigned int n_faces = 2 * dim;
      /// The mantle of a cylindrical domain.
      static constexpr unsigned int cylinder_wall_id = 2 * dim;

      static std::string
      face_name(const unsigned int boundary_id);

      static void
      declare_parameters(ParameterHandler &prm);
      /// @p domain gives face areas for flow-rate conditions; a cylindrical
      /// domain inscribed in it has its axis along @p cylinder_axis
      /// (numbers::invalid_unsigned_int: the box itself). @p file_mesh: the
      /// domain is a mesh file's (mesh/geometry = file), whose faces with
      /// ids 0..2 dim-1 need not be planes of the box: no flow-rate or
      /// symmetry conditions, and a wall id (cylinder_wall_id) for the rest.
      void
      parse_parameters(ParameterHandler       &prm,
                       const BoundingBox<dim> &domain,
                       const unsigned int cylinder_axis = numbers::invalid_unsigned_int,
                       const bool         file_mesh = false);

      /// Boundary ids of the domain: the box faces, and for a cylinder or a
      /// mesh file the wall id (cylinder_wall_id) after them.
      unsigned int
      n_boundary_ids() const
      {
        return n_faces +
               (cylinder_axis != numbers::invalid_unsigned_int || from_file ?
                  1 :
                  0);
      }

      /// Add the velocity constraints of all faces at @p time.
      void
      make_velocity_constraints(const DoFHandler<dim>     &dof_handler,
                                AffineConstraints<double> &constraints,
                                const double               time) const;

      const Face &
      face(const unsigned int boundary_id) const
      {
        return faces[boundary_id];
      }

      /// Whether face @p boundary_id imposes the velocity (wall, moving
      /// wall, velocity or flow rate): every type but pressure.
      bool
      imposes_velocity(const unsigned int boundary_id) const
      {
        return faces[boundary_id].type != Type::pressure;
      }

      /// Whether the pressure level is fixed: a pressure face or a
      /// pressure region.
      bool
      has_pressure_face() const;

      /// Reservoirs at a given pressure inside the inlet cylinder and
      /// outside the perimeter cylinder (subsections "inlet region" and
      /// "perimeter region"; see PressureRegion).
      const PressureRegion<dim> &
      inlet_region() const
      {
        return inlet;
      }
      const PressureRegion<dim> &
      perimeter_region() const
      {
        return perimeter;
      }
      /// The pressure region containing @p cell_center (inlet first), or
      /// nullptr.
      const PressureRegion<dim> *
      pressure_region(const Point<dim> &cell_center) const
      {
        return inlet.contains(cell_center)     ? &inlet :
               perimeter.contains(cell_center) ? &perimeter :
                                                 nullptr;
      }
      bool
      has_pressure_regions() const
      {
        return inlet.enabled() || perimeter.enabled();
      }

      /// The imposed velocity on a velocity / flow-rate face (for reference
      /// quantities such as the drag coefficient); zero if none.
      Tensor<1, dim>
      inflow_velocity() const;

      /**
       * Refuse imposed velocities whose fluxes do not add up to zero when no
       * face or region fixes the pressure: incompressible flow cannot carry
       * more out than in, and the solver would return a field that
       * satisfies neither (an outflow 3x the inflow gave a drag 3x off,
       * silently). Function faces are integrated at t = 0; a mesh file's
       * faces, whose areas are not known here, are not checked. Called by
       * parse_parameters().
       */
      void
      check_flux_balance() const;

      /// Area of face @p boundary_id of the box (of the circle for a
      /// cylinder's end); not defined for a mesh file's domain (NaN).
      double
      face_area(const unsigned int boundary_id) const;

    private:
      /// The box faces, then the cylinder's mantle (always no slip).
      std::array<Face, n_faces + 1> faces;
      PressureRegion<dim>           inlet, perimeter;
      BoundingBox<dim>              domain;
      unsigned int cylinder_axis = numbers::invalid_unsigned_int;
      bool         from_file     = false;
    };
  } // namespace fluid
} // namespace softsand

#endif
