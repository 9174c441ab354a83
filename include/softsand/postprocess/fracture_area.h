#ifndef softsand_postprocess_fracture_area_h
#define softsand_postprocess_fracture_area_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <softsand/dem/grain.h>
#include <softsand/fluid/pressure_region.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * Subsection "postprocessing/fracture area": the area of the open
     * channels connected to the inlet of a radial Hele-Shaw cell (the
     * paper's Fig. 9), from the grains projected on the plates.
     */
    struct FractureAreaParameters
    {
      bool   enabled = false;
      /// Pixel edge (m).
      double pixel_size = 0;
      /// A pixel is open where the gap-averaged solid fraction is below this
      /// (dimensionless).
      double open_threshold = 0.25;
      /// Sample points per pixel edge (the solid fraction is their mean).
      unsigned int samples = 4;
      /// Pixels farther than this from the inlet axis are closed (m; 0: the
      /// whole box): the open fluid outside the pack's walls is no fracture.
      double outer_radius = 0;
      /// Coupled runs end once the fracture reaches this distance from the
      /// inlet axis (m; 0: never).
      double stop_reach = 0;
      /// Coupled runs end once the fracture area grew by less than one
      /// pixel over this many coupling steps (0: no step count)...
      unsigned int stop_stall_steps = 0;
      /// ... and over this much simulated time (s; 0: no time span). With
      /// both set the window spans both: a Courant-limited step can be a
      /// sixteenth of the scene's, and 40 such steps only 2.5 ms.
      double stop_stall_time = 0;

      /// Whether the stall stop is on.
      bool
      stall_stop_set() const
      {
        return stop_stall_steps > 0 || stop_stall_time > 0;
      }

      /// Whether a coupled run may end at a developed fracture.
      bool
      stops_set() const
      {
        return stop_reach > 0 || stall_stop_set();
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };


    /**
     * The gap-averaged solid fraction of a layer of spheres between two
     * plates normal to z, on a pixel grid of the plate plane, and the open
     * pixels connected to a circular inlet.
     *
     * Solid fraction of a pixel: the mean, over samples x samples points of
     * the pixel, of (sum over grains of the length of the vertical chord
     * through the grain, clipped to the plates) / (gap), capped at 1 (the
     * small overlaps of settled grains count twice). Open: below the
     * threshold.
     * Connected: reached from the inlet pixels (centre within the inlet
     * radius) through edge-sharing open pixels (4-neighbour flood fill) that
     * lie within the outer radius. The fracture area is the area of the
     * connected pixels outside the inlet.
     */
    class FractureMap
    {
    public:
      /// The map of the box [@p lower, @p upper] of the plate plane (x, y)
      /// for plates at z = @p z_bottom and z = @p z_top, the inlet a circle
      /// of radius @p inlet_radius around @p inlet_center (x, y).
      FractureMap(const std::vector<dem::Grain<3>> &grains,
                  const Point<2>                   &lower,
                  const Point<2>                   &upper,
                  const double                      z_bottom,
                  const double                      z_top,
                  const Point<2>                   &inlet_center,
                  const double                      inlet_radius,
                  const FractureAreaParameters     &parameters);

      /// Area of the open pixels connected to the inlet, inlet excluded
      /// (m^2).
      double
      fracture_area() const
      {
        return area;
      }

      /// Largest distance from the inlet axis of a fracture pixel's centre
      /// (m; 0 when no open pixel touches the inlet).
      double
      reach() const
      {
        return largest_distance;
      }

      /// Area of one pixel (m^2).
      double
      pixel_area() const
      {
        return pixel * pixel;
      }

      /// Area of all open pixels within the outer radius, inlet excluded
      /// (m^2): connected or not.
      double
      open_area() const
      {
        return all_open_area;
      }

      /// Gap-averaged solid fraction of pixel (i, j).
      double
      solid_fraction(const unsigned int i, const unsigned int j) const
      {
        return solid[j * nx + i];
      }

      /// Whether pixel (i, j) belongs to the fracture.
      bool
      in_fracture(const unsigned int i, const unsigned int j) const
      {
        return state[j * nx + i] == connected;
      }

      unsigned int
      n_pixels_x() const
      {
        return nx;
      }
      unsigned int
      n_pixels_y() const
      {
        return ny;
      }

      /**
       * Write the map as a binary PGM image (row 0 at the top = largest y):
       * grey 0..200 the solid fraction 0..1 (capped), 255 the fracture.
       * Comment lines in the header give the step, the time @p time (s),
       * the pixel size and the extent (m), the fracture area and reach.
       */
      void
      write_pgm(const std::string &filename,
                const unsigned int step = 0,
                const double       time = 0) const;

    private:
      enum State : unsigned char
      {
        closed,
        open,
        inlet,
        connected
      };
      unsigned int       nx = 0, ny = 0;
      double             pixel = 0;
      Point<2>           origin;
      std::vector<float> solid;
      std::vector<State> state;
      double             area = 0, all_open_area = 0, largest_distance = 0;
    };


    /// The map of a radial Hele-Shaw cell: the plates at the z ends of the
    /// box [@p lower_corner, @p upper_corner], the inlet region's axis
    /// along z.
    FractureMap
    fracture_map_of_cell(const std::vector<dem::Grain<3>> &grains,
                         const fluid::PressureRegion<3>   &inlet,
                         const Point<3>                   &lower_corner,
                         const Point<3>                   &upper_corner,
                         const FractureAreaParameters     &parameters);
  } // namespace postprocess
} // namespace softsand

#endif
