#ifndef softsand_io_grain_file_h
#define softsand_io_grain_file_h

#include <softsand/dem/grain.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace io
  {
    /**
     * Plain-text grain packs, one grain per line, SI units:
     *   2D: x y radius [vx vy w]
     *   3D: x y z radius [vx vy vz wx wy wz]
     * '#' starts a comment; blank lines are skipped. Grains without
     * velocity columns are at rest. Plain text so that packs from other DEM
     * codes or scripts can be read without conversion.
     */

    /// Read a pack file; errors name the file, the line and the problem.
    template <int dim>
    std::vector<dem::Grain<dim>>
    read_grain_file(const std::string &filename);

    /// Write a pack with all columns at full precision, so that reading it
    /// back restores the grains exactly. The file is written to
    /// filename + ".tmp" and renamed, so that a run killed while writing
    /// never leaves a truncated pack. A @p note becomes a comment line of
    /// the header (e.g. that the pack was saved unsettled). Call it on one
    /// MPI rank only.
    template <int dim>
    void
    write_grain_file(const std::string                  &filename,
                     const std::vector<dem::Grain<dim>> &grains,
                     const std::string                  &note = "");
  } // namespace io
} // namespace softsand

#endif
