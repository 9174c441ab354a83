#ifndef softsand_postprocess_fracture_development_h
#define softsand_postprocess_fracture_development_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <softsand/dem/grain.h>
#include <softsand/fluid/pressure_region.h>
#include <softsand/postprocess/fracture_area.h>

#include <deque>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Whether an injection has reached a developed state, so that a coupled
     * run can end there instead of at a fixed time: the fracture reaches
     * `postprocessing/fracture area/stop at reach` from the inlet axis, or
     * its area grew by less than one pixel over a window of the last `stop
     * when stalled over` coupling steps and `stop when stalled for` seconds.
     * Judged on the fracture map of the grains at the start of each coupling
     * step (the map of that step's statistics row). The window's areas go
     * into the coupled checkpoint (save(), load()).
     */
    class FractureDevelopment
    {
    public:
      FractureDevelopment(const FractureAreaParameters   &parameters,
                          const fluid::PressureRegion<3> &inlet,
                          const Point<3>                 &lower_corner,
                          const Point<3>                 &upper_corner,
                          const MPI_Comm                  comm);

      /**
       * Record the map of @p grains at @p time (every rank holds them;
       * rank 0 computes it) and return why the fracture counts as
       * developed, or an empty string. Collective.
       */
      std::string
      check(const std::vector<dem::Grain<3>> &grains, const double time);

      /// The stall window's (time, area) checks, as text.
      void
      save(std::ostream &out) const;
      /// The window save() wrote.
      void
      load(std::istream &in);

    private:
      const FractureAreaParameters   parameters;
      const fluid::PressureRegion<3> inlet;
      const Point<3>                 lower_corner, upper_corner;
      const MPI_Comm                 mpi_communicator;
      /// Whether the check at @p index of `history` starts a full window.
      bool
      spans_window(const std::size_t index) const;

      /// (time in s, fracture area in m^2) of the checks back to the
      /// newest one that starts a full stall window.
      std::deque<std::pair<double, double>> history;
    };
  } // namespace postprocess
} // namespace softsand

#endif
