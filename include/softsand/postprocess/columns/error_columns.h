#ifndef softsand_postprocess_columns_error_columns_h
#define softsand_postprocess_columns_error_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /// Errors against an exact solution given as expressions of x, y, (z,)
    /// t (verification scenes): velocity L2 and H1 seminorm, pressure L2.
    template <int dim>
    class ErrorColumns : public FluidColumnSource<dim>
    {
    public:
      /// An empty @p exact_pressure means p = 0.
      ErrorColumns(const std::string &exact_velocity,
                   const std::string &exact_pressure);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const std::string expression;
    };
  } // namespace postprocess
} // namespace softsand

#endif
