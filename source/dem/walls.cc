#include <softsand/base/parameter_tools.h>
#include <softsand/dem/walls.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace dem
  {
    void
    Wall::advance(const double dt)
    {
      if (motion == Motion::servo)
        {
          // Positive error: the grains push less than the target, so the
          // wall moves towards them (along its normal).
          const double error = (target_pressure - pressure()) / target_pressure;
          error_integral += error * dt;
          double speed = max_velocity * (proportional_gain * error +
                                         integral_gain * error_integral);
          speed    = std::clamp(speed, -max_velocity, max_velocity);
          velocity = speed * normal;
        }
      if (motion != Motion::fixed)
        point += dt * velocity;
    }


    void
    WallParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("walls");
      prm.declare_entry(
        "box", "",
        Patterns::Anything(),
        "Fixed plane walls on these faces of the mesh box, comma-separated "
        "from x-, x+, y-, y+, z-, z+ (empty: none; 'all': the six).");
      prm.declare_entry(
        "list", "",
        Patterns::Anything(),
        "More walls, separated by ';'. Each is one of "
        "'plane px py pz nx ny nz fixed', "
        "'plane px py pz nx ny nz velocity vx vy vz', "
        "'plane px py pz nx ny nz servo' (driven to the servo pressure; the "
        "normal points to the grains), "
        "'cylinder px py pz ax ay az radius [inside|outside]' (a point on "
        "the axis, the axis, the radius; grains inside it, the default, or "
        "outside it: a post or the wall of an inlet).");
      prm.declare_entry(
        "octagon", "",
        Patterns::Anything(),
        "An octagon of 8 pistons (planes normal to the xy plane) of inradius "
        "R around (cx, cy): 'cx, cy, R'; or each piston at its own distance "
        "from the centre: 'cx, cy, R0, ..., R7' (piston k faces the "
        "direction k pi/4 from x; a compacted pack's last statistics row "
        "has piston_k_position = -Rk), the loaded area of each still the "
        "side of a regular octagon of inradius R0; empty: none. Plates are "
        "box walls z-, z+.");
      prm.declare_entry("octagon servo", "false", Patterns::Bool(),
                        "Drive the octagon's pistons to the servo pressure.");
      prm.declare_entry("servo pressure", "0", Patterns::Double(0),
                        "Target pressure of servo walls (Pa).");
      prm.declare_entry("servo max velocity", "0.01", Patterns::Double(0),
                        "Speed limit of servo walls (m/s).");
      prm.declare_entry("servo proportional gain", "1", Patterns::Double(0),
                        "Wall speed / max speed per relative pressure error.");
      prm.declare_entry("servo integral gain", "0", Patterns::Double(0),
                        "Integral gain of the servo (1/s).");
      prm.declare_entry("servo tolerance", "0.02", Patterns::Double(0),
                        "A pack counts as settled only with every servo wall "
                        "within this relative error of its target pressure.");
      prm.leave_subsection();
    }


    void
    WallParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("walls");
      box_faces = prm.get("box");
      list      = prm.get("list");
      if (!prm.get("octagon").empty())
        {
          const std::string text = prm.get("octagon");
          const auto n_values =
            Utilities::split_string_list(text, ',').size();
          octagon = base::get_double_list(prm, "octagon",
                                          n_values == 10 ? 10 : 3);
        }
      octagon_servo           = prm.get_bool("octagon servo");
      servo_pressure          = prm.get_double("servo pressure");
      servo_max_velocity      = prm.get_double("servo max velocity");
      servo_proportional_gain = prm.get_double("servo proportional gain");
      servo_integral_gain     = prm.get_double("servo integral gain");
      servo_tolerance         = prm.get_double("servo tolerance");
      const bool any_servo =
        octagon_servo || list.find("servo") != std::string::npos;
      if (any_servo && !(servo_pressure > 0))
        base::throw_invalid_parameter("dem/walls/servo pressure",
                                      prm.get("servo pressure"),
                                      "servo walls need a target pressure > 0 "
                                      "Pa");
      if (any_servo && !(servo_max_velocity > 0))
        base::throw_invalid_parameter("dem/walls/servo max velocity",
                                      prm.get("servo max velocity"),
                                      "servo walls need a speed limit > 0 m/s");
      prm.leave_subsection();
    }


    namespace
    {
      Wall
      make_plane(const std::string  &name,
                 const Point<3>     &point,
                 const Tensor<1, 3> &normal)
      {
        Wall w;
        w.name   = name;
        w.point  = point;
        w.normal = normal / normal.norm();
        return w;
      }

      void
      make_servo(Wall &w, const WallParameters &p, const double area)
      {
        w.motion            = Wall::Motion::servo;
        w.target_pressure   = p.servo_pressure;
        w.max_velocity      = p.servo_max_velocity;
        w.proportional_gain = p.servo_proportional_gain;
        w.integral_gain     = p.servo_integral_gain;
        w.area              = area;
      }
    } // namespace


    std::vector<Wall>
    create_walls(const WallParameters &p, const BoundingBox<3> &domain)
    {
      std::vector<Wall> walls;
      const auto [lo, hi] = domain.get_boundary_points();
      const Tensor<1, 3> extent = hi - lo;

      // Box faces.
      const std::vector<std::string> face_names = {"x-", "x+", "y-",
                                                   "y+", "z-", "z+"};
      std::vector<std::string> faces;
      {
        std::string spec = p.box_faces;
        std::replace(spec.begin(), spec.end(), ',', ' ');
        std::istringstream in(spec);
        std::string        f;
        while (in >> f)
          {
            if (f == "all")
              faces.insert(faces.end(), face_names.begin(), face_names.end());
            else if (std::find(face_names.begin(), face_names.end(), f) ==
                     face_names.end())
              base::throw_invalid_parameter("dem/walls/box", p.box_faces,
                                            "a comma-separated subset of x-, "
                                            "x+, y-, y+, z-, z+, or 'all'");
            else
              faces.push_back(f);
          }
      }
      for (const auto &f : faces)
        {
          const unsigned int d    = (f[0] - 'x');
          const bool         plus = (f[1] == '+');
          Tensor<1, 3>       n;
          n[d] = plus ? -1 : 1;
          Wall wall = make_plane("wall_" + std::string(1, f[0]) +
                                   (plus ? "max" : "min"),
                                 plus ? hi : lo,
                                 n);
          wall.area = extent[(d + 1) % 3] * extent[(d + 2) % 3];
          walls.push_back(wall);
        }

      // Octagon of pistons.
      if (!p.octagon.empty())
        {
          const double R = p.octagon[2];
          for (unsigned int k = 2; k < p.octagon.size(); ++k)
            if (!(p.octagon[k] > 0))
              base::throw_invalid_parameter("dem/walls/octagon",
                                            std::to_string(p.octagon[k]),
                                            "the inradius must be > 0");
          // Side of a regular octagon of inradius R: 2 R tan(pi/8).
          const double side = 2 * R * std::tan(M_PI / 8);
          for (unsigned int k = 0; k < 8; ++k)
            {
              const double angle = k * M_PI / 4;
              Tensor<1, 3> outward;
              outward[0] = std::cos(angle);
              outward[1] = std::sin(angle);
              Point<3> point(p.octagon[0], p.octagon[1], 0.5 * (lo[2] + hi[2]));
              point += (p.octagon.size() == 10 ? p.octagon[2 + k] : R) *
                       outward;
              Wall w = make_plane("piston_" + std::to_string(k), point, -outward);
              w.area = side * extent[2];
              if (p.octagon_servo)
                make_servo(w, p, side * extent[2]);
              walls.push_back(w);
            }
        }

      // Free list.
      std::istringstream list(p.list);
      std::string        item;
      unsigned int       count = 0;
      while (std::getline(list, item, ';'))
        {
          std::istringstream in(item);
          std::string        shape;
          if (!(in >> shape))
            continue;
          const auto bad = [&](const std::string &why) {
            base::throw_invalid_parameter("dem/walls/list", item, why);
          };
          double v[7];
          for (unsigned int i = 0; i < (shape == "cylinder" ? 7u : 6u); ++i)
            if (!(in >> v[i]))
              bad("expected 'plane px py pz nx ny nz MOTION' or 'cylinder px "
                  "py pz ax ay az radius [inside|outside]'");
          const Point<3>     point(v[0], v[1], v[2]);
          const Tensor<1, 3> dir({v[3], v[4], v[5]});
          if (!(dir.norm() > 0))
            bad("the normal or axis must be nonzero");
          const std::string name = "wall_" + std::to_string(count++);
          if (shape == "cylinder")
            {
              Wall w   = make_plane(name, point, dir);
              w.shape  = Wall::Shape::cylinder;
              w.radius = v[6];
              if (!(w.radius > 0))
                bad("the cylinder radius must be > 0");
              std::string side;
              if (in >> side)
                {
                  if (side == "outside")
                    w.outside = true;
                  else if (side != "inside")
                    bad("a cylinder's grains are 'inside' or 'outside' it");
                }
              const auto [s_min, s_max] = cylinder_axis_range(w, domain);
              w.area = 2 * M_PI * w.radius * std::max(s_max - s_min, 1e-300);
              walls.push_back(w);
              continue;
            }
          if (shape != "plane")
            bad("walls are 'plane' or 'cylinder'");
          Wall w = make_plane(name, point, dir);
          {
            // Loaded area: the box's cross-section normal to the wall.
            unsigned int axis = 0;
            for (unsigned int d = 1; d < 3; ++d)
              if (std::abs(w.normal[d]) > std::abs(w.normal[axis]))
                axis = d;
            w.area = extent[(axis + 1) % 3] * extent[(axis + 2) % 3];
          }
          std::string motion;
          in >> motion;
          if (motion == "fixed" || motion.empty())
            ;
          else if (motion == "velocity")
            {
              w.motion = Wall::Motion::velocity;
              for (unsigned int d = 0; d < 3; ++d)
                if (!(in >> w.velocity[d]))
                  bad("'velocity' needs three components vx vy vz");
            }
          else if (motion == "servo")
            make_servo(w, p, w.area);
          else
            bad("the motion is 'fixed', 'velocity vx vy vz' or 'servo'");
          walls.push_back(w);
        }

      // A plane inside a cylinder wall along its normal (a permeameter's
      // piston) loads the cylinder's cross-section, not the box's.
      for (auto &plane : walls)
        if (plane.shape == Wall::Shape::plane)
          for (const auto &c : walls)
            if (c.shape == Wall::Shape::cylinder && !c.outside &&
                std::abs(std::abs(plane.normal * c.normal) - 1) < 1e-9)
              plane.area = std::min(plane.area, M_PI * c.radius * c.radius);
      return walls;
    }


    namespace
    {
      std::string
      str(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }

      /// A point or direction as (x, y, z).
      std::string
      str(const Tensor<1, 3> &v)
      {
        std::ostringstream s;
        s << '(' << v[0] << ", " << v[1] << ", " << v[2] << ')';
        return s.str();
      }

      /// Where the user set the wall (box faces, octagon or list, by the
      /// names create_walls() gives) and its shape, for error messages.
      std::string
      describe(const Wall &wall)
      {
        std::string where = "dem/walls/list";
        if (wall.name.rfind("piston_", 0) == 0)
          where = "dem/walls/octagon";
        else if (wall.name.size() == 9 &&
                 (wall.name.substr(6) == "min" || wall.name.substr(6) == "max"))
          where = "dem/walls/box";
        if (wall.shape == Wall::Shape::plane)
          return "'" + wall.name + "' (" + where + ", the plane through " +
                 str(wall.point) + " with normal " + str(wall.normal) +
                 " towards the grains)";
        return "'" + wall.name + "' (" + where + ", the cylinder of radius " +
               str(wall.radius) + " m around the axis through " +
               str(wall.point) + " along " + str(wall.normal) + ", grains " +
               (wall.outside ? "outside" : "inside") + " it)";
      }
    } // namespace


    void
    check_wall_overlaps(const std::vector<Grain<3>> &grains,
                        const std::vector<Wall>     &walls,
                        const double                 max_overlap_ratio)
    {
      for (unsigned int i = 0; i < grains.size(); ++i)
        for (const Wall &wall : walls)
          {
            Tensor<1, 3> n;
            const double ratio =
              wall.overlap(grains[i].center, grains[i].radius, n) /
              grains[i].radius;
            AssertThrow(
              !(ratio > max_overlap_ratio),
              ExcMessage(
                "Grain " + std::to_string(i + 1) + " (counting from 1) at " +
                str(grains[i].center) + ", radius " + str(grains[i].radius) +
                " m, starts inside wall " + describe(wall) +
                ": it overlaps the wall by " + str(ratio) +
                " R, more than grains/max overlap ratio = " +
                str(max_overlap_ratio) +
                " allows (settled packs press a few % of R into their walls; "
                "more is a misplaced grain or wall, which the contact law "
                "would eject with a meaningless force). Move the grain or the wall, or leave the grain "
                "out."));
          }
    }


    namespace
    {
      /// Sutherland-Hodgman: the part of the convex polygon @p polygon where
      /// (x - point) * normal >= 0.
      std::vector<Point<3>>
      clip(const std::vector<Point<3>> &polygon,
           const Point<3>              &point,
           const Tensor<1, 3>          &normal)
      {
        std::vector<Point<3>> result;
        const unsigned int    n = polygon.size();
        for (unsigned int a = 0; a < n; ++a)
          {
            const Point<3> &p = polygon[a], &q = polygon[(a + 1) % n];
            const double    sp = (p - point) * normal, sq = (q - point) * normal;
            if (sp >= 0)
              result.push_back(p);
            if ((sp >= 0) != (sq >= 0))
              result.push_back(p + (sp / (sp - sq)) * (q - p));
          }
        return result;
      }
    } // namespace


    std::vector<Point<3>>
    plane_wall_face(const std::vector<Wall> &walls,
                    const unsigned int       k,
                    const BoundingBox<3>    &domain)
    {
      const Wall &wall = walls[k];
      Assert(wall.shape == Wall::Shape::plane, ExcInternalError());
      const auto [lo, hi] = domain.get_boundary_points();
      const Point<3>     centre = 0.5 * (lo + hi);
      const double       size   = 2 * (hi - lo).norm();
      const Tensor<1, 3> &n     = wall.normal;
      // A square in the plane around the box centre's projection, larger
      // than the box, then cut down.
      Tensor<1, 3> e1;
      e1[std::abs(n[0]) < 0.9 ? 0 : 1] = 1;
      e1 -= (e1 * n) * n;
      e1 /= e1.norm();
      const Tensor<1, 3> e2 = cross_product_3d(n, e1);
      const Point<3>     origin = centre - ((centre - wall.point) * n) * n;
      std::vector<Point<3>> square = {origin + size * (-e1 - e2),
                                      origin + size * (e1 - e2),
                                      origin + size * (e1 + e2),
                                      origin + size * (-e1 + e2)};
      for (unsigned int d = 0; d < 3; ++d)
        {
          Tensor<1, 3> axis;
          axis[d] = 1;
          square  = clip(square, lo, axis);
          square  = clip(square, hi, -axis);
        }
      std::vector<Point<3>> face = square;
      for (unsigned int j = 0; j < walls.size() && face.size() >= 3; ++j)
        if (j != k && walls[j].shape == Wall::Shape::plane)
          face = clip(face, walls[j].point, walls[j].normal);
      if (face.size() < 3)
        face = square;
      // Clipping through a vertex repeats it: drop repeats.
      std::vector<Point<3>> distinct;
      for (const auto &p : face)
        if (distinct.empty() || p.distance(distinct.back()) > 1e-12 * size)
          distinct.push_back(p);
      while (distinct.size() > 1 &&
             distinct.front().distance(distinct.back()) <= 1e-12 * size)
        distinct.pop_back();
      if (distinct.size() < 3)
        distinct.clear();
      return distinct;
    }


    std::pair<double, double>
    cylinder_axis_range(const Wall &cylinder, const BoundingBox<3> &domain)
    {
      double s_min = std::numeric_limits<double>::max(), s_max = -s_min;
      for (unsigned int v = 0; v < 8; ++v)
        {
          const double s = (domain.vertex(v) - cylinder.point) * cylinder.normal;
          s_min          = std::min(s_min, s);
          s_max          = std::max(s_max, s);
        }
      return {s_min, s_max};
    }
  } // namespace dem
} // namespace softsand
