#ifndef softsand_postprocess_columns_fracture_area_columns_h
#define softsand_postprocess_columns_fracture_area_columns_h

#include <softsand/fluid/pressure_region.h>
#include <softsand/postprocess/columns/fluid_column_source.h>
#include <softsand/postprocess/fracture_area.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * The area of the open channels connected to the inlet (the paper's
     * Fig. 9) and of all open pixels, from the grains between the plates;
     * with field output, the fracture map as a PGM file per row. A 3D cell
     * between plates normal to z.
     */
    class FractureAreaColumns : public FluidColumnSource<3>
    {
    public:
      FractureAreaColumns(const FractureAreaParameters   &parameters,
                          const fluid::PressureRegion<3> &inlet,
                          const Point<3>                 &lower_corner,
                          const Point<3>                 &upper_corner,
                          const std::string              &map_directory,
                          const MPI_Comm                  comm);

      void
      add_columns(const FluidSnapshot<3> &snapshot,
                  Columns                &row) const override;

      /// The map of the pack before the injection.
      void
      write_initial_files(const FluidSnapshot<3> &snapshot) const override;

    private:
      void
      write_map(const FractureMap &map, const FluidSnapshot<3> &s) const;

      const FractureAreaParameters   parameters;
      const fluid::PressureRegion<3> inlet;
      const Point<3>                 lower_corner, upper_corner;
      /// Empty: no map files.
      const std::string map_directory;
      const MPI_Comm    mpi_communicator;
    };
  } // namespace postprocess
} // namespace softsand

#endif
