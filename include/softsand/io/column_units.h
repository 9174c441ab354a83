#ifndef softsand_io_column_units_h
#define softsand_io_column_units_h

#include <string>

namespace softsand
{
  namespace io
  {
    /**
     * The SI unit of a statistics column of a 3D scene, by its name ("-" for
     * a number without unit; 2D scenes count per metre of depth). The
     * glossary of the columns is doc/statistics_columns.md.
     */
    std::string
    column_unit(const std::string &column);
  } // namespace io
} // namespace softsand

#endif
