#ifndef softsand_dem_walls_h
#define softsand_dem_walls_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <softsand/dem/grain.h>

#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /**
     * A rigid plane or cylinder that grains touch on one side. Planes are
     * fixed, move at a prescribed velocity, or are servo-controlled: they
     * move along their normal so that the grains' pressure on them reaches
     * a target (PI control, velocity limited), the way a triaxial cell's
     * pistons are driven.
     */
    struct Wall
    {
      enum class Shape
      {
        plane,
        cylinder
      };
      enum class Motion
      {
        fixed,
        velocity,
        servo
      };

      std::string  name;
      Shape        shape  = Shape::plane;
      Motion       motion = Motion::fixed;
      /// Plane: a point on it; cylinder: a point on the axis.
      Point<3>     point;
      /// Plane: unit normal pointing to the grains' side; cylinder: unit axis.
      Tensor<1, 3> normal;
      /// Cylinder radius.
      double       radius = 0;
      /// Cylinder: grains outside it (a post, e.g. the wall of an inlet
      /// that keeps grains out) instead of inside (a pipe).
      bool         outside = false;
      /// Current velocity (prescribed, or the servo's output).
      Tensor<1, 3> velocity;

      /// Servo: target pressure (Pa), loaded area (m^2), velocity limit
      /// (m/s), gains (proportional: dimensionless, integral: 1/s).
      double target_pressure = 0, area = 1, max_velocity = 0;
      double proportional_gain = 1, integral_gain = 0, error_integral = 0;

      /// Where the wall was when the grain-wall candidates were listed.
      Point<3>     point_at_build;

      /// Force that the grains exert on the wall in the last step (N).
      Tensor<1, 3> force;
      /// Sum over the grains touching the wall of their normal contact
      /// force on it (N, > 0 pushing): the load, also of a cylinder, whose
      /// force vector cancels around the axis.
      double       normal_force = 0;

      /// Grains' pressure on the wall (Pa): on a plane the force along
      /// -normal over its area, on a cylinder the normal load over its
      /// lateral area inside the domain box.
      double
      pressure() const
      {
        return (shape == Shape::plane ? -(force * normal) : normal_force) /
               area;
      }

      /// Overlap of a sphere (centre @p x, radius @p r) with the wall and
      /// the unit normal from the wall to the sphere; overlap <= 0: apart.
      /// Cylinders: grains inside, or outside if @p outside.
      inline double
      overlap(const Point<3> &x, const double r, Tensor<1, 3> &n) const
      {
        if (shape == Shape::plane)
          {
            n = normal;
            return r - (x - point) * normal;
          }
        Tensor<1, 3> radial = (x - point);
        radial -= (radial * normal) * normal;
        const double rho = radial.norm();
        if (outside)
          {
            // A grain on the axis has no outward direction: any is as good.
            n = (rho > 0 ? radial / rho : Tensor<1, 3>());
            return r - (rho - radius);
          }
        n = (rho > 0 ? -radial / rho : Tensor<1, 3>());
        return r - (radius - rho);
      }

      /// Servo update from the force measured this step, then move.
      void
      advance(const double dt);
    };

    /// Wall set of a scene: box faces, an octagon of pistons, and a list.
    struct WallParameters
    {
      std::string box_faces;
      std::string list;
      /// Octagon: centre (x, y), inradius, and whether the pistons are
      /// servo-driven to the servo pressure.
      std::vector<double> octagon;
      bool        octagon_servo = false;
      double      servo_pressure = 0, servo_max_velocity = 0.01;
      double      servo_proportional_gain = 1, servo_integral_gain = 0;
      /// A settled pack has every servo wall within this relative error.
      double      servo_tolerance = 0.02;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /// Build the walls of a scene in the box @p domain.
    std::vector<Wall>
    create_walls(const WallParameters &parameters, const BoundingBox<3> &domain);

    /**
     * Refuse a pack whose grains start inside a wall: a grain overlapping
     * a wall by more than @p max_overlap_ratio of its radius (a grain in an
     * inlet's cylinder wall, through a plate), the tolerance of the
     * grains' own overlaps (R* = R against a wall). Far more than a
     * settled pack's overlap is a misplaced grain or wall, which the
     * contact law would eject with a meaningless force. The error names
     * the grain (counting from 1), its centre, the wall and the overlap / R.
     */
    void
    check_wall_overlaps(const std::vector<Grain<3>> &grains,
                        const std::vector<Wall>     &walls,
                        const double                 max_overlap_ratio);

    /**
     * The face of plane wall @p k as drawn for output: the convex polygon
     * of the plane inside the box @p domain and on the grains' side of
     * every other plane wall (so a box's faces are its rectangles and an
     * octagon's pistons their sides between the neighbouring pistons and
     * the plates, following the walls as they move). If the other walls
     * cut the plane away entirely, the face is clipped by the box alone.
     * Vertices in order around the polygon; empty if the plane misses the
     * box.
     */
    std::vector<Point<3>>
    plane_wall_face(const std::vector<Wall> &walls,
                    const unsigned int       k,
                    const BoundingBox<3>    &domain);

    /// Range [s_min, s_max] of the axis coordinate (x - point) * axis of a
    /// cylinder wall over the box @p domain: the stretch drawn for output,
    /// and over which its lateral area is taken.
    std::pair<double, double>
    cylinder_axis_range(const Wall &cylinder, const BoundingBox<3> &domain);
  } // namespace dem
} // namespace softsand

#endif
