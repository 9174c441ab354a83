#ifndef softsand_io_column_units_h
#define softsand_io_column_units_h

#include <string>

namespace softsand
{
  namespace io
  {
    /**
     * The SI unit of a statistics column, by its name ("-" for a number
     * without unit). A 2D scene is a slice of unit depth: its forces,
     * energies, flow rates, volumes and error norms count per metre of
     * depth (N/m, J/m, m^2/s, m^2, ...). The glossary of the columns is
     * doc/statistics_columns.md.
     */
    std::string
    column_unit(const std::string &column, const unsigned int dim = 3);
  } // namespace io
} // namespace softsand

#endif
