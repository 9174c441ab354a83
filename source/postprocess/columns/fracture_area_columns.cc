#include <softsand/io/pvd_series.h>
#include <softsand/postprocess/columns/fracture_area_columns.h>


namespace softsand
{
  namespace postprocess
  {
    FractureAreaColumns::FractureAreaColumns(
      const FractureAreaParameters   &parameters,
      const fluid::PressureRegion<3> &inlet,
      const Point<3>                 &lower_corner,
      const Point<3>                 &upper_corner,
      const std::string              &map_directory,
      const MPI_Comm                  comm)
      : parameters(parameters)
      , inlet(inlet)
      , lower_corner(lower_corner)
      , upper_corner(upper_corner)
      , map_directory(map_directory)
      , mpi_communicator(comm)
    {}


    void
    FractureAreaColumns::add_columns(const FluidSnapshot<3> &s,
                                     Columns                &row) const
    {
      // Computed on rank 0 from the grains (every rank holds them).
      double areas[3] = {0, 0, 0};
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          const FractureMap map = fracture_map_of_cell(
            s.grains, inlet, lower_corner, upper_corner, parameters);
          areas[0] = map.fracture_area();
          areas[1] = map.open_area();
          areas[2] = map.reach();
          if (s.write_fields)
            write_map(map, s);
        }
      MPI_Bcast(areas, 3, MPI_DOUBLE, 0, mpi_communicator);
      row["fracture_area"] = areas[0];
      row["open_area"]     = areas[1];
      row["fracture_reach"] = areas[2];
    }


    void
    FractureAreaColumns::write_initial_files(const FluidSnapshot<3> &s) const
    {
      if (!map_directory.empty() &&
          Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        write_map(fracture_map_of_cell(
                    s.grains, inlet, lower_corner, upper_corner, parameters),
                  s);
    }


    void
    FractureAreaColumns::write_map(const FractureMap      &map,
                                   const FluidSnapshot<3> &s) const
    {
      if (map_directory.empty())
        return;
      map.write_pgm(map_directory + "/fracture_map_" +
                      io::PvdSeries::file_number(s.step) + ".pgm",
                    s.step,
                    s.time);
    }
  } // namespace postprocess
} // namespace softsand
