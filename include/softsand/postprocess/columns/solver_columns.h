#ifndef softsand_postprocess_columns_solver_columns_h
#define softsand_postprocess_columns_solver_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /// Mesh size and solver counts: cells, dofs, FGMRES iterations of the
    /// last solve and of all its nonlinear updates, nonlinear iterations.
    template <int dim>
    class SolverColumns : public FluidColumnSource<dim>
    {
    public:
      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;
    };
  } // namespace postprocess
} // namespace softsand

#endif
