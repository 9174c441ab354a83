#include <softsand/postprocess/columns/solver_columns.h>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    void
    SolverColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                    Columns                  &row) const
    {
      const auto &statistics   = s.fluid.get_statistics();
      row["cells"]             = s.triangulation.n_global_active_cells();
      row["dofs"]              = s.fluid.n_dofs();
      row["linear_iterations"] = statistics.linear_iterations;
      row["nonlinear_iterations"] = statistics.nonlinear_iterations;
      // All FGMRES iterations of this solve or step (Newton: every update).
      row["total_linear_iterations"] = statistics.total_linear_iterations;
    }

    template class SolverColumns<2>;
    template class SolverColumns<3>;
  } // namespace postprocess
} // namespace softsand
