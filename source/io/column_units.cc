#include <softsand/io/column_units.h>

#include <regex>
#include <utility>
#include <vector>

namespace softsand
{
  namespace io
  {
    std::string
    column_unit(const std::string &column, const unsigned int dim)
    {
      // First match wins: exact names, then families (grain0_vx, wall_0_*,
      // piston_3_*, ring_pressure_2, ...).
      static const std::vector<std::pair<std::regex, std::string>> units = {
        {std::regex("time|wall_time|coupling_time_step|cpu_s|wall_s"), "s"},
        {std::regex("kinetic_energy"), "J"},
        {std::regex("(mean|max)_speed|superficial_velocity|"
                    "radial_superficial_velocity|grain\\d+_v[xyz]"),
         "m/s"},
        {std::regex("grain\\d+_w[xyz]"), "rad/s"},
        {std::regex("grain\\d+_[xyz]|.*_position|fracture_reach"), "m"},
        {std::regex("pressure_drop|.*_pressure|ring_pressure_\\d+|"
                    "contact_stress_(xx|yy|zz)"),
         "Pa"},
        {std::regex(".*force.*|boundary_reaction_[xyz]"), "N"},
        {std::regex("flow_rate|outflow_rate|radial_flow_rate"), "m^3/s"},
        {std::regex("permeability|radial_permeability(_\\d+)?"), "m^2"},
        {std::regex("fracture_area|open_area"), "m^2"},
        {std::regex("open_pore_volume"), "m^3"},
        {std::regex("velocity_l2_error"), "m^2.5/s"},
        {std::regex("velocity_h1_error"), "m^1.5/s"},
        {std::regex("pressure_l2_error"), "Pa m^1.5"}};
      // 2D: the extensive quantities per metre of depth, the error norms
      // integrated over an area instead of a volume.
      static const std::vector<std::pair<std::string, std::string>>
        per_depth = {{"J", "J/m"},
                     {"N", "N/m"},
                     {"m^3/s", "m^2/s"},
                     {"m^3", "m^2"},
                     {"m^2.5/s", "m^2/s"},
                     {"m^1.5/s", "m/s"},
                     {"Pa m^1.5", "Pa m"}};
      for (const auto &[pattern, unit] : units)
        if (std::regex_match(column, pattern))
          {
            if (dim == 2)
              for (const auto &[in_3d, in_2d] : per_depth)
                if (unit == in_3d)
                  return in_2d;
            return unit;
          }
      return "-";
    }
  } // namespace io
} // namespace softsand
