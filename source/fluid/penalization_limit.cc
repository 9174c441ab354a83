#include <softsand/fluid/penalization_limit.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <unordered_set>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    std::unordered_map<types::global_dof_index, PenalizationLimitNode>
    penalization_limit_nodes(
      const DoFHandler<dim>                                     &dof,
      const SolidEvaluator<dim>                                 &evaluate,
      const std::function<bool(const CellAccessor<dim, dim> &)> &skip_cell)
    {
      const FiniteElement<dim> &element = dof.get_fe();
      // The velocity components share the first base element (Q2).
      const FiniteElement<dim> &scalar   = element.base_element(0);
      const unsigned int        n_scalar = scalar.n_dofs_per_cell();

      // One evaluation of the solids per cell: Gauss points (for the
      // integrals int_K (1 - vf) phi_k) followed by the scalar element's
      // support points (for the grain over each node), weights 0 there.
      const QGauss<dim>       gauss(scalar.degree + 1);
      const unsigned int      n_q         = gauss.size();
      std::vector<Point<dim>> unit_points = gauss.get_points();
      std::vector<double>     weights     = gauss.get_weights();
      for (const auto &p : scalar.get_unit_support_points())
        {
          unit_points.push_back(p);
          weights.push_back(0.);
        }
      FEValues<dim> values(scalar,
                           Quadrature<dim>(unit_points, weights),
                           update_values | update_quadrature_points |
                             update_JxW_values);

      struct Sums
      {
        double                              solid  = 0; // sum_K w_{K,k}
        double                              volume = 0; // sum_K int_K phi_k
        double                              target = 0; // sum_K w_{K,k} u_g
        std::vector<std::pair<int, double>> grains;
      };
      std::unordered_map<types::global_dof_index, Sums> sums;
      std::unordered_set<types::global_dof_index>       skipped;

      std::vector<types::global_dof_index> dof_indices(
        element.n_dofs_per_cell());
      std::vector<double> vf, solid_integral(n_scalar), integral(n_scalar);
      std::vector<Tensor<1, dim>> u_s;
      std::vector<int>            grain;
      const auto                  integrate = [&](std::vector<double> &result,
                                 const bool           solid) {
        std::fill(result.begin(), result.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double factor =
              (solid ? (grain[q] >= 0 ? 1. - vf[q] : 0.) : 1.) * values.JxW(q);
            for (unsigned int a = 0; a < n_scalar; ++a)
              result[a] += factor * values.shape_value(a, q);
          }
      };

      // The covered cells: the weights, the grains and their velocities.
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(dof_indices);
            if (skip_cell(*cell))
              {
                skipped.insert(dof_indices.begin(), dof_indices.end());
                continue;
              }
            values.reinit(typename Triangulation<dim>::cell_iterator(cell));
            evaluate(*cell, values.get_quadrature_points(), vf, u_s, grain);
            if (std::none_of(grain.begin(), grain.end(), [](const int g) {
                  return g >= 0;
                }))
              continue;
            integrate(solid_integral, true);
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              {
                const auto [c, a] = element.system_to_component_index(k);
                const int g       = grain[n_q + a];
                if (c >= dim || g < 0 || !(solid_integral[a] > 0))
                  continue;
                const double w = solid_integral[a];
                Sums        &s = sums[dof_indices[k]];
                s.solid += w;
                s.target += w * u_s[n_q + a][c];
                const auto share =
                  std::find_if(s.grains.begin(),
                               s.grains.end(),
                               [g](const auto &e) { return e.first == g; });
                if (share == s.grains.end())
                  s.grains.emplace_back(g, w);
                else
                  share->second += w;
              }
          }

      // Every cell around those nodes: int_K phi_k, the node's volume.
      for (const auto &cell : dof.active_cell_iterators())
        if (!cell->is_artificial() && !skip_cell(*cell))
          {
            cell->get_dof_indices(dof_indices);
            bool near_solid = false;
            for (unsigned int k = 0; k < dof_indices.size() && !near_solid; ++k)
              near_solid = sums.count(dof_indices[k]) > 0;
            if (!near_solid)
              continue;
            values.reinit(typename Triangulation<dim>::cell_iterator(cell));
            std::fill(integral.begin(), integral.end(), 0.);
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int a = 0; a < n_scalar; ++a)
                integral[a] += values.shape_value(a, q) * values.JxW(q);
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              {
                const auto [c, a] = element.system_to_component_index(k);
                if (c >= dim)
                  continue;
                const auto s = sums.find(dof_indices[k]);
                if (s != sums.end())
                  s->second.volume += integral[a];
              }
          }

      std::unordered_map<types::global_dof_index, PenalizationLimitNode> nodes;
      for (const auto &[i, s] : sums)
        if (skipped.count(i) == 0 && s.volume > 0)
          {
            PenalizationLimitNode &node = nodes[i];
            node.void_fraction          = 1. - std::min(1., s.solid / s.volume);
            node.target                 = s.target / s.solid;
            for (const auto &[g, w] : s.grains)
              node.grain_shares.emplace_back(g, w / s.solid);
            // The largest share first: the node's grain where one is named.
            std::sort(node.grain_shares.begin(),
                      node.grain_shares.end(),
                      [](const auto &x, const auto &y) {
                        return x.second > y.second;
                      });
          }
      return nodes;
    }

    template std::unordered_map<types::global_dof_index, PenalizationLimitNode>
    penalization_limit_nodes(
      const DoFHandler<2> &,
      const SolidEvaluator<2> &,
      const std::function<bool(const CellAccessor<2, 2> &)> &);
    template std::unordered_map<types::global_dof_index, PenalizationLimitNode>
    penalization_limit_nodes(
      const DoFHandler<3> &,
      const SolidEvaluator<3> &,
      const std::function<bool(const CellAccessor<3, 3> &)> &);
  } // namespace fluid
} // namespace softsand
