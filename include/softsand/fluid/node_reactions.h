// The fluid's reaction on the grains' rigid nodes, summed per grain and
// node as the rows are gathered: a node's cells and components add into one
// record, as they add in the grain's force and torque (both are sums over
// the records, so only round-off depends on the order).
#ifndef softsand_fluid_node_reactions_h
#define softsand_fluid_node_reactions_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <cstddef>
#include <functional>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    using namespace dealii;

    /// Call @p add(grain, w) for the grain rigid DoF @p i belongs to, with
    /// w = @p weight; where the node's target blends grains (penalization
    /// limit, @p shares), once per grain with its share of @p weight.
    template <typename Add>
    void
    for_each_grain_share(
      const std::unordered_map<types::global_dof_index, int> &grain_of_dof,
      const std::unordered_map<types::global_dof_index,
                               std::vector<std::pair<int, double>>> &shares,
      const types::global_dof_index                                  i,
      const double                                                   weight,
      const Add                                                     &add)
    {
      const auto blended = shares.find(i);
      if (blended == shares.end())
        add(grain_of_dof.at(i), weight);
      else
        for (const auto &[grain, share] : blended->second)
          add(grain, weight * share);
    }

    template <int dim>
    class NodeReactionSum
    {
    public:
      /// One record per grain and node: (grain, node position, force).
      using Records = std::vector<std::tuple<int, Point<dim>, Tensor<1, dim>>>;

      void
      reserve(const std::size_t n_nodes)
      {
        sums.reserve(n_nodes);
      }

      /// Add @p value to component @p component of the reaction of @p grain
      /// on the node identified by @p node (any one DoF index of the node,
      /// the same for all its components) at @p position.
      void
      add(const int                     grain,
          const types::global_dof_index node,
          const Point<dim>             &position,
          const unsigned int            component,
          const double                  value)
      {
        sums.try_emplace(std::make_pair(grain, node), position, Tensor<1, dim>())
          .first->second.second[component] += value;
      }

      /// Append the records to @p records and forget them.
      void
      move_to(Records &records)
      {
        records.reserve(records.size() + sums.size());
        for (const auto &[key, reaction] : sums)
          records.emplace_back(key.first, reaction.first, reaction.second);
        sums.clear();
      }

    private:
      struct Hash
      {
        std::size_t
        operator()(const std::pair<int, types::global_dof_index> &k) const
        {
          return std::hash<types::global_dof_index>()(k.second) * 31 +
                 std::hash<int>()(k.first);
        }
      };
      std::unordered_map<std::pair<int, types::global_dof_index>,
                         std::pair<Point<dim>, Tensor<1, dim>>,
                         Hash>
        sums;
    };
  } // namespace fluid
} // namespace softsand

#endif
