#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/fracture_area.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>

namespace softsand
{
  namespace postprocess
  {
    void
    FractureAreaParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      prm.enter_subsection("fracture area");
      prm.declare_entry(
        "enabled",
        "false",
        Patterns::Bool(),
        "Report the area of the open channels connected to the inlet "
        "(statistics columns fracture_area and open_area, m^2): the grains' "
        "solid fraction averaged across the gap between the plates (z min "
        "and z max of the mesh box) on a pixel grid of the xy plane, "
        "pixels below the open threshold flood-filled from the inlet "
        "(boundary conditions/inlet region, axis along z). Writes "
        "fracture_map_NNNNN.pgm with each field output.");
      prm.declare_entry("pixel size",
                        "0",
                        Patterns::Double(0),
                        "Pixel edge (m); 0: a quarter of the mean grain "
                        "diameter.");
      prm.declare_entry("open threshold",
                        "0.25",
                        Patterns::Double(0, 1),
                        "A pixel is open where the gap-averaged solid "
                        "fraction is below this (dimensionless, in (0, 1)).");
      prm.declare_entry("samples",
                        "4",
                        Patterns::Integer(1, 64),
                        "Sample points per pixel edge: a pixel's solid "
                        "fraction is the mean over samples^2 points.");
      prm.declare_entry("outer radius",
                        "0",
                        Patterns::Double(0),
                        "Pixels farther than this from the inlet axis are "
                        "never open (m; 0: the whole box): the grain-free "
                        "fluid outside the pack's walls is no fracture.");
      prm.declare_entry("stop at reach",
                        "0",
                        Patterns::Double(0),
                        "Coupled runs: end the run (a developed fracture) "
                        "once the fracture reaches this distance from the "
                        "inlet axis (m; statistics column fracture_reach; "
                        "0: never). Must lie between the inlet radius and "
                        "the outer radius.");
      prm.declare_entry("stop when stalled over",
                        "0",
                        Patterns::Integer(0),
                        "Coupled runs: end the run (a developed fracture) "
                        "once the fracture area grew by less than one pixel "
                        "over this many coupling steps (0: no count of "
                        "steps). The areas of the window are kept in the "
                        "checkpoint: a restarted run stops where the "
                        "uninterrupted one would.");
      prm.declare_entry("stop when stalled for",
                        "0",
                        Patterns::Double(0),
                        "Coupled runs: end the run (a developed fracture) "
                        "once the fracture area grew by less than one pixel "
                        "over this much simulated time (s; 0: no time "
                        "span). With 'stop when stalled over' also set, the "
                        "window spans both the steps and the time (40 steps "
                        "halved to the Courant limit can be 2.5 ms).");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    void
    FractureAreaParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      prm.enter_subsection("fracture area");
      enabled        = prm.get_bool("enabled");
      pixel_size     = prm.get_double("pixel size");
      open_threshold = prm.get_double("open threshold");
      samples        = prm.get_integer("samples");
      outer_radius   = prm.get_double("outer radius");
      stop_reach       = prm.get_double("stop at reach");
      stop_stall_steps = prm.get_integer("stop when stalled over");
      stop_stall_time  = prm.get_double("stop when stalled for");
      const std::string stop_name = stop_reach > 0 ? "stop at reach" :
                                    stop_stall_steps > 0 ?
                                                     "stop when stalled over" :
                                                     "stop when stalled for";
      if (!enabled && stops_set())
        base::throw_invalid_parameter(
          "postprocessing/fracture area/" + stop_name,
          prm.get(stop_name),
          "0 unless 'postprocessing/fracture area/enabled = true' (the "
          "stop is judged on the fracture map)");
      if (stop_reach > 0 && outer_radius > 0 && stop_reach >= outer_radius)
        base::throw_invalid_parameter(
          "postprocessing/fracture area/stop at reach",
          prm.get("stop at reach"),
          "below 'outer radius' = " + prm.get("outer radius") +
            " m (no fracture pixel lies beyond it)");
      if (enabled && !(open_threshold > 0 && open_threshold < 1))
        base::throw_invalid_parameter(
          "postprocessing/fracture area/open threshold",
          prm.get("open threshold"),
          "a solid fraction strictly between 0 and 1");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    FractureMap::FractureMap(const std::vector<dem::Grain<3>> &grains,
                             const Point<2>                   &lower,
                             const Point<2>                   &upper,
                             const double                      z_bottom,
                             const double                      z_top,
                             const Point<2>                   &inlet_center,
                             const double                      inlet_radius,
                             const FractureAreaParameters     &parameters)
      : origin(lower)
    {
      AssertThrow(z_top > z_bottom, ExcMessage("The plates must enclose a gap."));
      pixel = parameters.pixel_size;
      if (!(pixel > 0))
        {
          double sum = 0;
          for (const auto &g : grains)
            sum += g.diameter();
          pixel = grains.empty() ? (upper[0] - lower[0]) / 100 :
                                   0.25 * sum / grains.size();
        }
      nx = std::max(1, int(std::ceil((upper[0] - lower[0]) / pixel - 1e-9)));
      ny = std::max(1, int(std::ceil((upper[1] - lower[1]) / pixel - 1e-9)));
      solid.assign(nx * ny, 0.f);
      state.assign(nx * ny, closed);

      // Chords through each grain, clipped to the plates, at the sample
      // points of the pixels under its disc.
      const unsigned int  m    = parameters.samples;
      const double        gap  = z_top - z_bottom;
      const double        step = pixel / m;
      std::vector<double> column(m * m);
      for (const auto &g : grains)
        {
          const double r = g.radius;
          const int    i0 = std::max(0, int(std::floor((g.center[0] - r - origin[0]) / pixel)));
          const int    i1 = std::min(int(nx) - 1, int(std::floor((g.center[0] + r - origin[0]) / pixel)));
          const int    j0 = std::max(0, int(std::floor((g.center[1] - r - origin[1]) / pixel)));
          const int    j1 = std::min(int(ny) - 1, int(std::floor((g.center[1] + r - origin[1]) / pixel)));
          for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
              {
                double sum = 0;
                for (unsigned int b = 0; b < m; ++b)
                  for (unsigned int a = 0; a < m; ++a)
                    {
                      const double x  = origin[0] + i * pixel + (a + 0.5) * step;
                      const double y  = origin[1] + j * pixel + (b + 0.5) * step;
                      const double r2 = (x - g.center[0]) * (x - g.center[0]) +
                                        (y - g.center[1]) * (y - g.center[1]);
                      if (r2 >= r * r)
                        continue;
                      const double half  = std::sqrt(r * r - r2);
                      const double chord = std::min(g.center[2] + half, z_top) -
                                           std::max(g.center[2] - half, z_bottom);
                      if (chord > 0)
                        sum += chord;
                    }
                // Overlapping grains count twice where they overlap (a few
                // % of R* in settled packs); the pixel mean is capped at 1.
                solid[j * nx + i] += float(sum / (gap * m * m));
              }
        }
      for (auto &s : solid)
        s = std::min(s, 1.f);

      const double outer2 = parameters.outer_radius > 0 ?
                              parameters.outer_radius * parameters.outer_radius :
                              std::numeric_limits<double>::max();
      std::deque<unsigned int> front;
      const double             pixel_area = pixel * pixel;
      // Squared distance of pixel k's centre from the inlet axis.
      const auto distance2 = [&](const unsigned int k) {
        const double dx = origin[0] + (k % nx + 0.5) * pixel - inlet_center[0];
        const double dy = origin[1] + (k / nx + 0.5) * pixel - inlet_center[1];
        return dx * dx + dy * dy;
      };
      for (unsigned int j = 0; j < ny; ++j)
        for (unsigned int i = 0; i < nx; ++i)
          {
            const unsigned int k  = j * nx + i;
            const double       d2 = distance2(k);
            if (d2 < inlet_radius * inlet_radius)
              {
                state[k] = inlet;
                front.push_back(k);
              }
            else if (d2 <= outer2 && solid[k] < parameters.open_threshold)
              {
                state[k] = open;
                all_open_area += pixel_area;
              }
          }
      // Flood fill from the inlet through edge-sharing open pixels.
      while (!front.empty())
        {
          const unsigned int k = front.front();
          front.pop_front();
          const unsigned int i = k % nx, j = k / nx;
          const auto         visit = [&](const unsigned int n) {
            if (state[n] == open)
              {
                state[n] = connected;
                area += pixel_area;
                largest_distance =
                  std::max(largest_distance, std::sqrt(distance2(n)));
                front.push_back(n);
              }
          };
          if (i > 0)
            visit(k - 1);
          if (i + 1 < nx)
            visit(k + 1);
          if (j > 0)
            visit(k - nx);
          if (j + 1 < ny)
            visit(k + nx);
        }
    }


    FractureMap
    fracture_map_of_cell(const std::vector<dem::Grain<3>> &grains,
                         const fluid::PressureRegion<3>   &inlet,
                         const Point<3>                   &lower_corner,
                         const Point<3>                   &upper_corner,
                         const FractureAreaParameters     &parameters)
    {
      return FractureMap(grains,
                         Point<2>(lower_corner[0], lower_corner[1]),
                         Point<2>(upper_corner[0], upper_corner[1]),
                         lower_corner[2],
                         upper_corner[2],
                         Point<2>(inlet.center[0], inlet.center[1]),
                         inlet.radius,
                         parameters);
    }


    void
    FractureMap::write_pgm(const std::string &filename,
                           const unsigned int step,
                           const double       time) const
    {
      std::ofstream out(filename, std::ios::binary);
      out << "P5\n"
          << "# softsand fracture map: step " << step << ", time " << time
          << " s\n"
          << "# pixel " << pixel << " m; x from " << origin[0] << " to "
          << origin[0] + nx * pixel << " m (left to right), y from "
          << origin[1] << " to " << origin[1] + ny * pixel
          << " m (bottom to top)\n"
          << "# grey 0..200: gap-averaged solid fraction 0..1; 255: the "
             "fracture connected to the inlet\n"
          << "# fracture area " << area << " m^2, reach " << largest_distance
          << " m\n"
          << nx << ' ' << ny << "\n255\n";
      std::vector<unsigned char> row(nx);
      for (unsigned int j = ny; j-- > 0;)
        {
          for (unsigned int i = 0; i < nx; ++i)
            row[i] = state[j * nx + i] == connected ?
                       255 :
                       static_cast<unsigned char>(
                         std::lround(200 * solid[j * nx + i]));
          out.write(reinterpret_cast<const char *>(row.data()), nx);
        }
    }
  } // namespace postprocess
} // namespace softsand
