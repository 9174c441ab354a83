#ifndef softsand_coupling_grain_mesh_refinement_h
#define softsand_coupling_grain_mesh_refinement_h

#include <deal.II/distributed/tria.h>

#include <softsand/coupling/grain_locator.h>

namespace softsand
{
  namespace coupling
  {
    using namespace dealii;

    /**
     * Refine every cell cut by a grain surface until its edge is at most
     * @p target_cell_size (the smallest grain diameter over the cells per
     * diameter), leaving grain interiors and open fluid coarse; p4est keeps
     * the 2:1 balance. With @p uniform the whole mesh is refined to that
     * size instead (for adaptive-vs-uniform comparisons). Returns the number
     * of refinement sweeps.
     */
    template <int dim>
    unsigned int
    refine_around_grains(parallel::distributed::Triangulation<dim> &tria,
                         const GrainLocator<dim>                   &locator,
                         const double       target_cell_size,
                         const unsigned int max_level,
                         const bool         uniform);

    /**
     * Flag the mesh to follow moving grains (no execution): refine cells
     * within @p margin of a grain surface whose edge is above
     * @p target_cell_size; coarsen cells finer than @p base_level whose
     * parent (grown by @p margin) meets no grain surface, i.e. grain
     * interiors and open fluid the grains have left. The margin lets grains
     * move that far before the mesh must follow. Returns whether any cell
     * of any rank is flagged (after p4est's 2:1 smoothing).
     */
    template <int dim>
    bool
    flag_cells_around_grains(parallel::distributed::Triangulation<dim> &tria,
                             const GrainLocator<dim>                   &locator,
                             const double       target_cell_size,
                             const double       margin,
                             const unsigned int base_level,
                             const unsigned int max_level);

    /// Smallest cell edge of the mesh (over all ranks).
    template <int dim>
    double
    min_cell_edge(const parallel::distributed::Triangulation<dim> &tria);
  } // namespace coupling
} // namespace softsand

#endif
