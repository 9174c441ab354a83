#include <softsand/coupling/grain_locator.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace softsand
{
  namespace coupling
  {
    template <int dim>
    GrainLocator<dim>::GrainLocator(const std::vector<dem::Grain<dim>> &grains)
      : grain_list(grains)
    {
      for (unsigned int d = 0; d < dim; ++d)
        n_bins[d] = 1;
      if (grains.empty())
        {
          bins.resize(1);
          return;
        }
      Point<dim> lo = grains[0].center, hi = grains[0].center;
      double     r_max = 0;
      min_grain_diameter = std::numeric_limits<double>::max();
      for (const auto &g : grains)
        {
          r_max              = std::max(r_max, g.radius);
          min_grain_diameter = std::min(min_grain_diameter, g.diameter());
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], g.center[d] - g.radius);
              hi[d] = std::max(hi[d], g.center[d] + g.radius);
            }
        }
      max_radius = r_max;
      bin_size   = 2 * r_max;
      origin     = lo;
      // Keep the grid to a few million bins even for very spread-out sets.
      std::size_t total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          n_bins[d] = std::max(1, int(std::ceil((hi[d] - lo[d]) / bin_size)));
          total *= n_bins[d];
        }
      while (total > 4000000)
        {
          bin_size *= 2;
          total = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              n_bins[d] =
                std::max(1, int(std::ceil((hi[d] - lo[d]) / bin_size)));
              total *= n_bins[d];
            }
        }
      bins.resize(total);
      for (unsigned int i = 0; i < grains.size(); ++i)
        bins[flat_index(bin_of(grains[i].center))].push_back(i);
    }


    template <int dim>
    std::array<int, dim>
    GrainLocator<dim>::bin_of(const Point<dim> &x) const
    {
      std::array<int, dim> b;
      for (unsigned int d = 0; d < dim; ++d)
        b[d] = std::clamp(int(std::floor((x[d] - origin[d]) / bin_size)),
                          0,
                          n_bins[d] - 1);
      return b;
    }


    template <int dim>
    unsigned int
    GrainLocator<dim>::flat_index(const std::array<int, dim> &b) const
    {
      unsigned int i = 0;
      for (int d = dim - 1; d >= 0; --d)
        i = i * n_bins[d] + b[d];
      return i;
    }


    template <int dim>
    void
    GrainLocator<dim>::grains_near_box(const BoundingBox<dim>    &box,
                                       std::vector<unsigned int> &indices) const
    {
      indices.clear();
      if (grain_list.empty())
        return;
      // A grain meets the box only if its centre lies within max_radius of
      // it: scan the bins of the box grown by max_radius (for a point, 2
      // bins per direction instead of the 3 of the box's bin grown by one).
      Point<dim> lo = box.get_boundary_points().first,
                 hi = box.get_boundary_points().second;
      for (unsigned int d = 0; d < dim; ++d)
        {
          // Boxes entirely beyond the grains' extent meet none.
          if (hi[d] < origin[d] - bin_size ||
              lo[d] > origin[d] + (n_bins[d] + 1) * bin_size)
            return;
        }
      // (A margin over max_radius keeps rounding from dropping a grain.)
      const double reach    = max_radius * (1. + 1e-9);
      Point<dim>   reach_lo = lo, reach_hi = hi;
      for (unsigned int d = 0; d < dim; ++d)
        {
          reach_lo[d] -= reach;
          reach_hi[d] += reach;
        }
      const std::array<int, dim> b0 = bin_of(reach_lo), b1 = bin_of(reach_hi);
      std::array<int, dim> b = b0;
      while (true)
        {
          for (const unsigned int i : bins[flat_index(b)])
            {
              const auto &g  = grain_list[i];
              bool        ok = true;
              for (unsigned int d = 0; d < dim && ok; ++d)
                ok = (g.center[d] + g.radius >= lo[d]) &&
                     (g.center[d] - g.radius <= hi[d]);
              if (ok)
                indices.push_back(i);
            }
          unsigned int d = 0;
          for (; d < dim; ++d)
            {
              if (++b[d] <= b1[d])
                break;
              b[d] = b0[d];
            }
          if (d == dim)
            break;
        }
    }


    template <int dim>
    int
    GrainLocator<dim>::containing_grain(const Point<dim> &x) const
    {
      return containing_grain(x, 0.);
    }


    template <int dim>
    int
    GrainLocator<dim>::containing_grain(const Point<dim> &x,
                                        const double      inflation) const
    {
      thread_local std::vector<unsigned int> near;
      BoundingBox<dim> box(std::make_pair(x, x));
      if (inflation > 0)
        box.extend(inflation);
      grains_near_box(box, near);
      return containing_grain(x, inflation, near);
    }


    template <int dim>
    int
    GrainLocator<dim>::containing_grain(
      const Point<dim>                &x,
      const double                     inflation,
      const std::vector<unsigned int> &candidates) const
    {
      int    best       = -1;
      double best_depth = 0;
      for (const unsigned int i : candidates)
        {
          const auto  &g     = grain_list[i];
          const double reach = g.radius + inflation;
          const double d2    = x.distance_square(g.center);
          if (d2 > reach * reach)
            continue; // depth < 0
          const double depth = reach - std::sqrt(d2);
          if (depth > best_depth || (best < 0 && depth >= 0))
            {
              best       = i;
              best_depth = depth;
            }
        }
      return best;
    }


    template <int dim>
    typename GrainLocator<dim>::BoxRelation
    GrainLocator<dim>::classify_box(const BoundingBox<dim> &box,
                                    int                    &grain_index) const
    {
      thread_local std::vector<unsigned int> near;
      return classify_box(box, grain_index, near);
    }


    template <int dim>
    typename GrainLocator<dim>::BoxRelation
    GrainLocator<dim>::classify_box(const BoundingBox<dim>    &box,
                                    int                       &grain_index,
                                    std::vector<unsigned int> &near) const
    {
      grains_near_box(box, near);
      grain_index      = -1;
      bool cut         = false;
      const auto &lo   = box.get_boundary_points().first;
      const auto &hi   = box.get_boundary_points().second;
      for (const unsigned int i : near)
        {
          const auto &g = grain_list[i];
          // Nearest and farthest distances from the centre to the box.
          double near2 = 0, far2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double c  = g.center[d];
              const double dn = std::max({lo[d] - c, 0., c - hi[d]});
              const double df = std::max(std::abs(c - lo[d]), std::abs(c - hi[d]));
              near2 += dn * dn;
              far2 += df * df;
            }
          const double r2 = g.radius * g.radius;
          if (far2 <= r2)
            {
              grain_index = i;
              return BoxRelation::inside_one;
            }
          if (near2 < r2)
            cut = true;
        }
      return cut ? BoxRelation::cut : BoxRelation::outside_all;
    }

    template class GrainLocator<2>;
    template class GrainLocator<3>;
  } // namespace coupling
} // namespace softsand
