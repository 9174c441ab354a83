#ifndef softsand_fluid_penalization_limit_h
#define softsand_fluid_penalization_limit_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/tria_accessor.h>

#include <deal.II/lac/affine_constraints.h>

#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /**
     * The Theta -> infinity limit of the paper's penalized update (Eq. 6),
     * node by node (fluid/solid model = penalization limit). Each velocity
     * node k of a cell that solids cover gets one blended target t_k, the
     * average of the rigid velocities of the grains over it in the cells
     * around it weighted by w_{K,k} = int_K (1 - vf) phi_k, and is
     * constrained to u_k = vf_k u^n_k + (1 - vf_k) t_k, with
     * 1 - vf_k = sum_K w_{K,k} / sum_K int_K phi_k. No node is asked to
     * follow two rigid motions, so Theta leaves the system.
     */
    struct PenalizationLimitNode
    {
      /// vf_k of the node (dimensionless).
      double void_fraction = 1;
      /// t_k, the blended rigid velocity component of the node (m/s).
      double target = 0;
      /// The grains whose rigid motion enters t_k and their shares of it
      /// (summing to 1): the node's reaction is split among them alike.
      std::vector<std::pair<int, double>> grain_shares;
    };

    /// The solid field of a cell at points (void fraction, rigid velocity,
    /// solid index), as the assembly sees it.
    template <int dim>
    using SolidEvaluator = std::function<void(const CellAccessor<dim, dim> &,
                                              const std::vector<Point<dim>> &,
                                              std::vector<double> &,
                                              std::vector<Tensor<1, dim>> &,
                                              std::vector<int> &)>;

    /**
     * The velocity DoFs of @p dof (velocity components first, then the
     * pressure, as PenalizedNavierStokes numbers them) that a solid covers
     * in some cell around them, with their blended target and void
     * fraction. Cells for which @p skip_cell is true (freed contact cells)
     * contribute nothing and their nodes are left out. Every non-artificial
     * cell is visited, so the values are complete for the DoFs of locally
     * owned cells.
     */
    template <int dim>
    std::unordered_map<types::global_dof_index, PenalizationLimitNode>
    penalization_limit_nodes(
      const DoFHandler<dim>                                     &dof,
      const SolidEvaluator<dim>                                 &evaluate,
      const std::function<bool(const CellAccessor<dim, dim> &)> &skip_cell);
  } // namespace fluid
} // namespace softsand

#endif
