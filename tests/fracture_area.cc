// The fracture-area postprocessor (postprocess::FractureMap) on synthetic
// grain layouts with known answers.
//
// 1. Volume: one sphere between plates 1 mm apart, partly cut by the top
//    plate; the gap-averaged solid fraction integrated over the plate plane
//    times the gap must give the volume of the sphere between the plates
//    (a spherical cap removed), within the sampling error.
// 2. Channel: a single layer of 1 mm grains spanning the gap (h = 1 mm) on
//    a lattice dense enough (spacing 0.25 mm x 0.25 mm) that every pixel
//    has a solid fraction above 0.9, except where the grains were removed:
//    a straight channel 0.25 mm wide from the inlet (radius ~1 mm) to
//    x = 3 mm, and an isolated pocket 0.75 x 0.75 mm elsewhere. The grains
//    removed are those whose disc reaches into the channel or pocket; the
//    remaining ones touch their edges, which lie on pixel edges (0.125 mm
//    pixels), and the inlet circle crosses the channel's two pixel rows
//    between pixel centres at x = 1 mm. Exact answers: fracture area
//    0.25 mm x (3 - 1) mm = 0.5 mm^2; open area 0.5 + 0.5625 mm^2. The
//    reach is the centre of the channel's last pixels, (23.5, +-0.5) pixels
//    from the axis.
// 3. Developed fracture (postprocess::FractureDevelopment) on that layout:
//    the reach stop holds at 2.9 mm and not at 3.0 mm; the stall stop over
//    2 steps holds at the third check of an unchanged map and not before,
//    and not when the channel is lengthened by 2 pixels between the second
//    and third checks (the area grows by 4 pixels). Over 2 steps and 3 ms
//    with checks 1 ms apart it holds at the fourth check, also in a copy
//    loaded from the window saved after the second check (a restart).

#include <softsand/postprocess/fracture_area.h>
#include <softsand/postprocess/fracture_development.h>

#include "tests.h"

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace softsand;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // 1. One sphere (r = 0.4 mm, centre 0.7 mm above the bottom plate, so
  //    0.1 mm sticks out through the top plate at 1 mm).
  {
    dem::Grain<3> g;
    g.radius = 0.4e-3;
    g.center = Point<3>(0.05e-3, -0.02e-3, 0.7e-3);
    postprocess::FractureAreaParameters p;
    p.enabled    = true;
    p.pixel_size = 0.05e-3;
    p.samples    = 8;
    const double                   h = 1e-3;
    const postprocess::FractureMap map({g},
                                       Point<2>(-0.6e-3, -0.6e-3),
                                       Point<2>(0.6e-3, 0.6e-3),
                                       0,
                                       h,
                                       Point<2>(),
                                       0,
                                       p);
    double sum = 0;
    for (unsigned int j = 0; j < map.n_pixels_y(); ++j)
      for (unsigned int i = 0; i < map.n_pixels_x(); ++i)
        sum += map.solid_fraction(i, j);
    const double volume = sum * p.pixel_size * p.pixel_size * h;
    // Cap of height c = 0.1 mm above the top plate: pi c^2 (3 r - c) / 3.
    const double c     = 0.1e-3;
    const double exact = 4. / 3. * M_PI * std::pow(g.radius, 3) -
                         M_PI * c * c * (3 * g.radius - c) / 3;
    deallog << "volume from the map / sphere volume between the plates - 1 "
            << "within 2e-3: "
            << (std::abs(volume / exact - 1) < 2e-3 ? "yes" : "NO")
            << std::endl;
  }

  // 2. Channel and pocket in a dense layer.
  {
    const double s = 0.125e-3; // pixel
    const double h = 8 * s, r = 4 * s;
    // Open rectangles (xmin, xmax, ymin, ymax): the channel, the pocket.
    const double rects[2][4] = {{0, 24 * s, -s, s},
                                {-22 * s, -16 * s, -3 * s, 3 * s}};
    const auto distance_to = [](const double *rect, const double x,
                                const double y) {
      const double dx = std::max({rect[0] - x, 0., x - rect[1]});
      const double dy = std::max({rect[2] - y, 0., y - rect[3]});
      return std::sqrt(dx * dx + dy * dy);
    };
    std::vector<dem::Grain<3>> grains;
    // Centres at even multiples of s in x, odd multiples in y.
    for (int i = -30; i <= 30; ++i)
      for (int j = -30; j <= 29; ++j)
        {
          const double x = 2 * i * s, y = (2 * j + 1) * s;
          if (distance_to(rects[0], x, y) < r - 1e-12 * s ||
              distance_to(rects[1], x, y) < r - 1e-12 * s)
            continue;
          dem::Grain<3> g;
          g.radius = r;
          g.center = Point<3>(x, y, 0.5 * h);
          grains.push_back(g);
        }
    postprocess::FractureAreaParameters p;
    p.enabled        = true;
    p.pixel_size     = s;
    p.open_threshold = 0.25;
    p.samples        = 4;
    const double inlet_radius = std::sqrt(64 * s * s + 0.25 * s * s);
    const postprocess::FractureMap map(grains,
                                       Point<2>(-40 * s, -40 * s),
                                       Point<2>(40 * s, 40 * s),
                                       0,
                                       h,
                                       Point<2>(),
                                       inlet_radius,
                                       p);
    // Smallest solid fraction of a closed pixel outside the inlet.
    double       closed_min = 1;
    unsigned int n_fracture = 0;
    for (unsigned int j = 0; j < map.n_pixels_y(); ++j)
      for (unsigned int i = 0; i < map.n_pixels_x(); ++i)
        {
          const double x = -40 * s + (i + 0.5) * s, y = -40 * s + (j + 0.5) * s;
          const bool   in_open = distance_to(rects[0], x, y) == 0 ||
                               distance_to(rects[1], x, y) == 0;
          if (x * x + y * y >= inlet_radius * inlet_radius && !in_open)
            closed_min = std::min(closed_min, map.solid_fraction(i, j));
          n_fracture += map.in_fracture(i, j);
        }
    deallog << "grains " << grains.size()
            << ", every other pixel above the threshold: "
            << (closed_min > p.open_threshold ? "yes" : "NO") << std::endl;
    deallog << "fracture area " << std::setprecision(4)
            << map.fracture_area() * 1e6 << " mm^2 (exact 0.5), open area "
            << map.open_area() * 1e6 << " mm^2 (exact 1.0625), fracture "
            << "pixels " << n_fracture << " (exact 32)" << std::setprecision(6)
            << std::endl;
    deallog << "exact: "
            << (std::abs(map.fracture_area() - 0.5e-6) < 1e-12 &&
                    std::abs(map.open_area() - 1.0625e-6) < 1e-12 ?
                  "yes" :
                  "NO")
            << std::endl;
    const double exact_reach = s * std::sqrt(23.5 * 23.5 + 0.25);
    deallog << "reach " << std::setprecision(5) << map.reach() * 1e3
            << " mm (exact " << exact_reach * 1e3 << "): "
            << (std::abs(map.reach() - exact_reach) < 1e-12 ? "yes" : "NO")
            << std::setprecision(6) << std::endl;

    // 3. Developed fracture.
    fluid::PressureRegion<3> inlet;
    inlet.is_enabled = true;
    inlet.radius     = inlet_radius;
    inlet.axis[2]    = 1;
    const Point<3> lower(-40 * s, -40 * s, 0), upper(40 * s, 40 * s, h);
    const auto     says = [](const std::string &why) {
      return why.empty() ? std::string("no") : "yes (" + why + ")";
    };
    for (const double stop : {2.9e-3, 3.0e-3})
      {
        p.stop_reach = stop;
        postprocess::FractureDevelopment development(
          p, inlet, lower, upper, MPI_COMM_WORLD);
        deallog << "stop at reach " << stop * 1e3
                << " mm: " << says(development.check(grains, 0)) << std::endl;
      }
    p.stop_reach       = 0;
    p.stop_stall_steps = 2;
    {
      postprocess::FractureDevelopment development(
        p, inlet, lower, upper, MPI_COMM_WORLD);
      for (unsigned int k = 1; k <= 3; ++k)
        deallog << "unchanged map, check " << k << ", stalled: "
                << says(development.check(grains, 1e-3 * k)) << std::endl;
    }
    // The window over 2 steps and 3 ms, checks 1 ms apart: the time span
    // decides (check 4). A copy made from the window saved after check 2,
    // as a restart reads it, stops at the same check.
    p.stop_stall_time = 3e-3;
    {
      postprocess::FractureDevelopment development(
        p, inlet, lower, upper, MPI_COMM_WORLD);
      std::stringstream saved;
      for (unsigned int k = 1; k <= 4; ++k)
        {
          deallog << "2 steps and 3 ms, check " << k << ", stalled: "
                  << says(development.check(grains, 1e-3 * k)) << std::endl;
          if (k == 2)
            development.save(saved);
        }
      postprocess::FractureDevelopment restarted(
        p, inlet, lower, upper, MPI_COMM_WORLD);
      restarted.load(saved);
      for (unsigned int k = 3; k <= 4; ++k)
        deallog << "restarted after check 2, check " << k << ", stalled: "
                << says(restarted.check(grains, 1e-3 * k)) << std::endl;
    }
    p.stop_stall_time = 0;
    {
      postprocess::FractureDevelopment development(
        p, inlet, lower, upper, MPI_COMM_WORLD);
      // The channel lengthened by 2 pixels at the third check: the grains
      // reaching into [24 s, 26 s] x [-s, s] go, which opens 4 pixels.
      std::vector<dem::Grain<3>> growing = grains;
      const double extension[4] = {24 * s, 26 * s, -s, s};
      for (unsigned int k = 1; k <= 3; ++k)
        {
          if (k == 3)
            growing.erase(std::remove_if(growing.begin(),
                                         growing.end(),
                                         [&](const dem::Grain<3> &g) {
                                           return distance_to(extension,
                                                              g.center[0],
                                                              g.center[1]) <
                                                  r - 1e-12 * s;
                                         }),
                          growing.end());
          deallog << "growing map, check " << k << ", stalled: "
                  << says(development.check(growing, 1e-3 * k)) << std::endl;
        }
    }
  }
}
