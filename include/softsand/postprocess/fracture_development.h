#ifndef softsand_postprocess_fracture_development_h
#define softsand_postprocess_fracture_development_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <softsand/dem/grain.h>
#include <softsand/fluid/pressure_region.h>
#include <softsand/postprocess/fracture_area.h>

#include <deque>
#include <string>
#include <vector>

namespace softsand
{
  namespace postprocess
  {
    /**
     * Whether an injection has reached a developed state, so that a coupled
     * run can end there instead of at a fixed time: the fracture reaches
     * `postprocessing/fracture area/stop at reach` from the inlet axis, or
     * its area grew by less than one pixel over the last `stop when stalled
     * over` coupling steps. Judged on the fracture map of the grains at the
     * start of each coupling step (the map of that step's statistics row).
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
       * Record the map of @p grains (every rank holds them; rank 0 computes
       * it) and return why the fracture counts as developed, or an empty
       * string. Collective.
       */
      std::string
      check(const std::vector<dem::Grain<3>> &grains);

    private:
      const FractureAreaParameters   parameters;
      const fluid::PressureRegion<3> inlet;
      const Point<3>                 lower_corner, upper_corner;
      const MPI_Comm                 mpi_communicator;
      /// Fracture areas of the last stop_stall_steps + 1 checks (m^2).
      std::deque<double> areas;
    };
  } // namespace postprocess
} // namespace softsand

#endif
