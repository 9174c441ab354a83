#ifndef softsand_io_wall_output_h
#define softsand_io_wall_output_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>

#include <softsand/dem/walls.h>
#include <softsand/io/pvd_series.h>

#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    /**
     * Walls for ParaView, beside the grains: one VTU per output (written by
     * rank 0; the walls are the same on every rank) and a PVD series. A
     * plane is drawn as its face inside the domain box and behind the other
     * planes (dem::plane_wall_face(): a box's rectangles, an octagon's
     * sides), a cylinder as a ring of quadrilaterals over the box. Cell
     * data: wall index (the order of the statistics columns), the force of
     * the grains on the wall and its normal load (N), the pressure (Pa),
     * the servo target pressure (Pa, 0 if not servo-driven), the wall
     * velocity (m/s).
     */
    class WallOutput
    {
    public:
      WallOutput(const std::string    &directory,
                 const std::string    &base_name,
                 const BoundingBox<3> &domain);

      /// The walls at @p time, after step @p step, in BASE_NNNNN.vtu.
      void
      write(const std::vector<dem::Wall> &walls,
            const double                  time,
            const unsigned long           step,
            const MPI_Comm                comm);

      /// A restarted run continues the series of the run it resumes at
      /// @p time (see PvdSeries::resume()).
      void
      resume(const double time)
      {
        series.resume(time);
      }

      /// Quadrilaterals around a cylinder in the drawing.
      static constexpr unsigned int cylinder_segments = 64;

    private:
      std::string                                 directory;
      std::string                                 base_name;
      BoundingBox<3>                              domain;
      PvdSeries                                   series;
    };
  } // namespace io
} // namespace softsand

#endif
