#ifndef softsand_postprocess_columns_grain_columns_h
#define softsand_postprocess_columns_grain_columns_h

#include <deal.II/base/bounding_box.h>

#include <softsand/dem/granular_dynamics.h>
#include <softsand/io/statistics_file.h>

namespace softsand
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * The grains' statistics columns, one list for granular and coupled
     * scenes: kinetic energy, speeds, overlaps, coordination, the stability
     * rates of the DEM step, the packing fraction and the normal contact
     * stresses in the probe box, grains present and lost, neighbour-list
     * builds, and each wall's normal force, pressure and (plane walls)
     * position.
     */
    class GrainColumns
    {
    public:
      explicit GrainColumns(const BoundingBox<3> &probe);

      /// Adds the columns to the statistics row; returns the statistics.
      dem::GranularStatistics
      add_columns(const dem::GranularDynamics &dem,
                  io::StatisticsFile          &statistics,
                  const MPI_Comm               comm) const;

    private:
      const BoundingBox<3> probe;
    };

    /// The first grain's position, velocity and angular velocity (zeros
    /// when no grain is left: the columns stay).
    void
    add_first_grain_columns(const std::vector<dem::Grain<3>> &grains,
                            io::StatisticsFile               &statistics);
  } // namespace postprocess
} // namespace softsand

#endif
