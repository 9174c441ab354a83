#include <deal.II/base/exceptions.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/dem/pack_generators.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace dem
  {
    namespace
    {
      /// Beyond this a lattice or pack is almost certainly a unit mistake
      /// (mm for m) and would only end in an out-of-memory kill.
      constexpr double max_grains = 5e7;

      /// Relative slack of the no-overlap checks, so that touching grains
      /// typed with rounded decimals are accepted.
      constexpr double overlap_tolerance = 1e-9;

      std::string
      str(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }

      template <int dim>
      std::string
      str(const Point<dim> &p)
      {
        std::ostringstream s;
        s << '(';
        for (unsigned int d = 0; d < dim; ++d)
          s << (d == 0 ? "" : ", ") << p[d];
        s << ')';
        return s.str();
      }

      /// Uniform in [0, 1) with 53 random bits (genrand_res53): unlike
      /// std::uniform_real_distribution, the same on every library.
      double
      uniform01(std::mt19937 &rng)
      {
        const double a = rng() >> 5, b = rng() >> 6;
        return (a * 67108864. + b) / 9007199254740992.;
      }

      /// Standard normal by Box-Muller (one value per call, no state).
      double
      standard_normal(std::mt19937 &rng)
      {
        const double u1 = 1. - uniform01(rng); // in (0, 1]
        const double u2 = uniform01(rng);
        return std::sqrt(-2. * std::log(u1)) * std::cos(2. * M_PI * u2);
      }

      double
      normal_cdf(const double x)
      {
        return 0.5 * std::erfc(-x / std::sqrt(2.));
      }

      template <int dim>
      double
      ball_measure(const double radius)
      {
        Grain<dim> g;
        g.radius = radius;
        return g.measure();
      }

      void
      check_positive(const std::string &entry, const double value)
      {
        if (!(value > 0) || !std::isfinite(value))
          base::throw_invalid_parameter(entry,
                                        str(value),
                                        "it must be a finite number > 0 m");
      }

      void
      check_range(const std::string &kind,
                  const double       min_diameter,
                  const double       max_diameter)
      {
        check_positive("grains/min diameter", min_diameter);
        if (!(max_diameter > min_diameter) || !std::isfinite(max_diameter))
          base::throw_invalid_parameter(
            "grains/max diameter",
            str(max_diameter),
            "the " + kind + " size distribution needs a max diameter above "
              "grains/min diameter = " + str(min_diameter) + " m");
      }


      /**
       * Uniform grid over a box with cells at least @p min_cell_size wide,
       * holding grain indices as linked lists. With cells no smaller than
       * the largest diameter, overlapping grains are always in neighbouring
       * cells, so each test looks at 3^dim cells only.
       */
      template <int dim>
      class CellList
      {
      public:
        CellList(const BoundingBox<dim> &box,
                 const double            min_cell_size,
                 const std::size_t       n_grains)
          : lower(box.get_boundary_points().first)
          , next(n_grains, -1)
        {
          const Point<dim> upper = box.get_boundary_points().second;
          // Cap the cell count near the grain count: a few large grains in a
          // big box must not allocate a huge empty grid.
          const double max_cells = 4. * n_grains + 64.;
          double       h         = min_cell_size;
          while (true)
            {
              double n_cells = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double side = upper[d] - lower[d];
                  n[d] = static_cast<unsigned int>(
                    std::max(1., std::min(std::floor(side / h), 1e9)));
                  inverse_width[d] = n[d] / std::max(side, 1e-300);
                  n_cells *= n[d];
                }
              if (n_cells <= max_cells)
                break;
              h *= 1.5;
            }
          std::size_t n_cells = 1;
          for (unsigned int d = 0; d < dim; ++d)
            n_cells *= n[d];
          head.assign(n_cells, -1);
        }

        void
        insert(const unsigned int grain, const Point<dim> &p)
        {
          const std::size_t c = flat_index(cell_of(p));
          next[grain]         = head[c];
          head[c]             = grain;
        }

        /// Call @p f(j) for the grains in the cells around @p p until it
        /// returns true; returns whether it did.
        template <typename F>
        bool
        any_near(const Point<dim> &p, const F &f) const
        {
          const std::array<int, dim> c = cell_of(p);
          std::array<int, dim>       lo, hi, k;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::max(c[d] - 1, 0);
              hi[d] = std::min(c[d] + 1, static_cast<int>(n[d]) - 1);
              k[d]  = lo[d];
            }
          while (true)
            {
              for (int j = head[flat_index(k)]; j >= 0; j = next[j])
                if (f(static_cast<unsigned int>(j)))
                  return true;
              unsigned int d = 0;
              for (; d < dim; ++d)
                if (++k[d] <= hi[d])
                  break;
                else
                  k[d] = lo[d];
              if (d == dim)
                return false;
            }
        }

      private:
        std::array<int, dim>
        cell_of(const Point<dim> &p) const
        {
          std::array<int, dim> c;
          for (unsigned int d = 0; d < dim; ++d)
            c[d] = static_cast<int>(std::clamp(
              std::floor((p[d] - lower[d]) * inverse_width[d]),
              0.,
              n[d] - 1.));
          return c;
        }

        std::size_t
        flat_index(const std::array<int, dim> &c) const
        {
          std::size_t i = 0;
          for (int d = dim - 1; d >= 0; --d)
            i = i * n[d] + c[d];
          return i;
        }

        Point<dim>                   lower;
        std::array<unsigned int, dim> n;
        std::array<double, dim>       inverse_width;
        std::vector<int>              head;
        std::vector<int>              next;
      };


      /// Lattice layout along one axis: count and first centre.
      struct Axis
      {
        unsigned int n;
        double       first;
      };

      /// The cells of edge @p spacing that fit in @p region along each axis
      /// (at least one, then centred, for single-layer packs).
      template <int dim>
      std::array<Axis, dim>
      lattice_axes(const BoundingBox<dim> &region,
                   const double            diameter,
                   const double            spacing)
      {
        const auto [lower, upper] = region.get_boundary_points();
        std::array<Axis, dim> axes;
        double                n_total = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double side = upper[d] - lower[d];
            if (!(side >= diameter * (1. - overlap_tolerance)))
              base::throw_invalid_parameter(
                "grains/diameter",
                str(diameter),
                "the grains do not fit in the lattice region " + str(lower) +
                  " - " + str(upper) + " (side " + str(side) +
                  " m along axis " + std::to_string(d) + ")");
            const double n = std::floor(side / spacing + 1e-9);
            if (n >= 1)
              axes[d] = {static_cast<unsigned int>(std::min(n, 1e9)),
                         lower[d] + 0.5 * spacing};
            else
              axes[d] = {1, lower[d] + 0.5 * side};
            n_total *= std::max(n, 1.);
          }
        if (n_total > max_grains)
          base::throw_invalid_parameter(
            "grains/lattice spacing",
            str(spacing),
            "the lattice would hold " + str(n_total) + " grains (at most " +
              str(max_grains) + " allowed); check the units (m)");
        return axes;
      }

      /// Append one grain per point of the lattice first + spacing * i.
      template <int dim>
      void
      add_lattice(const std::array<Axis, dim> &axes,
                  const double                 spacing,
                  const double                 diameter,
                  std::vector<Grain<dim>>     &grains)
      {
        std::size_t n_total = 1;
        for (const Axis &a : axes)
          n_total *= a.n;
        grains.reserve(grains.size() + n_total);
        for (std::size_t k = 0; k < n_total; ++k)
          {
            Grain<dim>  g;
            std::size_t rest = k;
            for (unsigned int d = 0; d < dim; ++d)
              {
                g.center[d] = axes[d].first + spacing * (rest % axes[d].n);
                rest /= axes[d].n;
              }
            g.radius = 0.5 * diameter;
            grains.push_back(g);
          }
      }
    } // namespace


    SizeDistribution::SizeDistribution(const Kind   kind,
                                       const double a,
                                       const double b,
                                       const double lower,
                                       const double upper)
      : type(kind)
      , a(a)
      , b(b)
      , lower(lower)
      , upper(upper)
    {}


    SizeDistribution
    SizeDistribution::constant(const double diameter)
    {
      check_positive("grains/diameter", diameter);
      return SizeDistribution(Kind::constant, diameter, 0, diameter, diameter);
    }


    SizeDistribution
    SizeDistribution::discrete(const std::vector<double> &diameters,
                               const std::vector<double> &mass_fractions)
    {
      if (diameters.empty() || diameters.size() != mass_fractions.size())
        base::throw_invalid_parameter(
          "grains/discrete fractions",
          std::to_string(mass_fractions.size()) + " value(s)",
          "give one mass fraction per entry of 'grains/discrete diameters' (" +
            std::to_string(diameters.size()) + ")");
      double total = 0;
      for (unsigned int k = 0; k < diameters.size(); ++k)
        {
          check_positive("grains/discrete diameters", diameters[k]);
          if (!(mass_fractions[k] >= 0))
            base::throw_invalid_parameter("grains/discrete fractions",
                                          str(mass_fractions[k]),
                                          "fractions must be >= 0");
          // Number probability of a size: its mass fraction over its mass.
          total += mass_fractions[k] / std::pow(diameters[k], 3);
        }
      if (!(total > 0))
        base::throw_invalid_parameter("grains/discrete fractions", "all 0",
                                      "at least one fraction must be > 0");
      SizeDistribution d(Kind::discrete,
                         0,
                         0,
                         *std::min_element(diameters.begin(), diameters.end()),
                         *std::max_element(diameters.begin(), diameters.end()));
      d.sizes = diameters;
      double sum = 0;
      for (unsigned int k = 0; k < diameters.size(); ++k)
        {
          sum += mass_fractions[k] / std::pow(diameters[k], 3) / total;
          d.cumulative.push_back(sum);
        }
      d.cumulative.back() = 1;
      return d;
    }


    SizeDistribution
    SizeDistribution::uniform(const double min_diameter,
                              const double max_diameter)
    {
      check_range("uniform", min_diameter, max_diameter);
      return SizeDistribution(
        Kind::uniform, 0, 0, min_diameter, max_diameter);
    }


    SizeDistribution
    SizeDistribution::truncated_normal(const double mean,
                                       const double sd,
                                       const double min_diameter,
                                       const double max_diameter)
    {
      check_positive("grains/mean diameter", mean);
      check_positive("grains/diameter standard deviation", sd);
      check_range("truncated normal", min_diameter, max_diameter);
      // Rejection sampling must not loop (almost) forever.
      const double mass = normal_cdf((max_diameter - mean) / sd) -
                          normal_cdf((min_diameter - mean) / sd);
      if (!(mass >= 1e-6))
        base::throw_invalid_parameter(
          "grains/mean diameter",
          str(mean),
          "a normal distribution of this mean and standard deviation " +
            str(sd) + " m puts almost no diameters (fraction " + str(mass) +
            ") in [" + str(min_diameter) + ", " + str(max_diameter) +
            "] m; move the mean towards that range or widen it");
      return SizeDistribution(
        Kind::truncated_normal, mean, sd, min_diameter, max_diameter);
    }


    SizeDistribution
    SizeDistribution::lognormal(const double mean,
                                const double sd,
                                const double min_diameter,
                                const double max_diameter)
    {
      check_positive("grains/mean diameter", mean);
      check_positive("grains/diameter standard deviation", sd);
      if (!(min_diameter >= 0) || !std::isfinite(min_diameter))
        base::throw_invalid_parameter("grains/min diameter",
                                      str(min_diameter),
                                      "it must be a finite number >= 0 m");
      const bool truncated = max_diameter > 0;
      if (truncated && !(max_diameter > min_diameter &&
                         std::isfinite(max_diameter)))
        base::throw_invalid_parameter(
          "grains/max diameter",
          str(max_diameter),
          "the lognormal size distribution needs either 0 (no upper bound) "
          "or a max diameter above grains/min diameter = " +
            str(min_diameter) + " m");

      // Parameters of log(d) that give d the requested mean and sd.
      const double sigma2 = std::log1p(sd * sd / (mean * mean));
      const double sigma  = std::sqrt(sigma2);
      const double mu     = std::log(mean) - 0.5 * sigma2;

      const double upper =
        truncated ? max_diameter : std::numeric_limits<double>::infinity();
      const double mass =
        (truncated ? normal_cdf((std::log(max_diameter) - mu) / sigma) : 1.) -
        (min_diameter > 0 ? normal_cdf((std::log(min_diameter) - mu) / sigma) :
                            0.);
      if (!(mass >= 1e-6))
        base::throw_invalid_parameter(
          "grains/mean diameter",
          str(mean),
          "a lognormal distribution of this mean and standard deviation " +
            str(sd) + " m puts almost no diameters (fraction " + str(mass) +
            ") in [" + str(min_diameter) + ", " + str(upper) +
            "] m; move the mean towards that range or widen it");
      return SizeDistribution(Kind::lognormal, mu, sigma, min_diameter, upper);
    }


    double
    SizeDistribution::draw(std::mt19937 &rng) const
    {
      switch (type)
        {
          case Kind::constant:
            return a;
          case Kind::discrete:
            {
              const double u = uniform01(rng);
              for (unsigned int k = 0; k < sizes.size(); ++k)
                if (u < cumulative[k])
                  return sizes[k];
              return sizes.back();
            }
          case Kind::uniform:
            return lower + (upper - lower) * uniform01(rng);
          case Kind::truncated_normal:
          case Kind::lognormal:
            // The constructors ensure an acceptance rate >= 1e-6.
            for (unsigned long i = 0; i < 1000000000ul; ++i)
              {
                const double z = standard_normal(rng);
                const double d = type == Kind::truncated_normal ?
                                   a + b * z :
                                   std::exp(a + b * z);
                if (d >= lower && d <= upper && d > 0)
                  return d;
              }
            AssertThrow(false,
                        ExcMessage("Internal error: rejection sampling of "
                                   "the grain size distribution failed."));
        }
      return a;
    }


    template <int dim>
    SizeDistribution
    make_size_distribution(const GrainParameters<dim> &p)
    {
      const std::string &kind = p.size_distribution;
      if (kind == "constant")
        return SizeDistribution::constant(p.diameter);
      if (kind == "uniform")
        return SizeDistribution::uniform(p.min_diameter, p.max_diameter);
      if (kind == "truncated normal")
        return SizeDistribution::truncated_normal(p.mean_diameter,
                                                  p.diameter_sd,
                                                  p.min_diameter,
                                                  p.max_diameter);
      if (kind == "lognormal")
        return SizeDistribution::lognormal(p.mean_diameter,
                                           p.diameter_sd,
                                           p.min_diameter,
                                           p.max_diameter);
      if (kind == "discrete")
        return SizeDistribution::discrete(p.discrete_diameters,
                                          p.discrete_fractions);
      base::throw_invalid_parameter(
        "grains/size distribution",
        kind,
        "allowed are constant, uniform, truncated normal, lognormal and "
        "discrete");
    }


    template <int dim>
    std::vector<Grain<dim>>
    simple_cubic_array(const BoundingBox<dim> &region,
                       const double            diameter,
                       const double            spacing)
    {
      check_positive("grains/diameter", diameter);
      check_positive("grains/lattice spacing", spacing);
      if (spacing < diameter * (1. - overlap_tolerance))
        base::throw_invalid_parameter(
          "grains/lattice spacing",
          str(spacing),
          "the simple cubic centre distance must be >= grains/diameter = " +
            str(diameter) + " m, else neighbouring grains overlap");
      std::vector<Grain<dim>> grains;
      add_lattice<dim>(lattice_axes(region, diameter, spacing),
                  spacing,
                  diameter,
                  grains);
      return grains;
    }


    template <int dim>
    std::vector<Grain<dim>>
    bcc_array(const BoundingBox<dim> &region,
              const double            diameter,
              const double            cube_edge)
    {
      check_positive("grains/diameter", diameter);
      check_positive("grains/lattice spacing", cube_edge);
      // The closest pairs are corner and body centre, half a cube diagonal
      // apart; corner pairs (one edge apart) are farther for dim <= 3.
      const double min_edge = 2. * diameter / std::sqrt(1. * dim);
      if (cube_edge < min_edge * (1. - overlap_tolerance))
        base::throw_invalid_parameter(
          "grains/lattice spacing",
          str(cube_edge),
          "the bcc cube edge must be >= 2 / sqrt(" + std::to_string(dim) +
            ") * grains/diameter = " + str(min_edge) +
            " m (corner to body centre is half the cube diagonal), else "
            "grains overlap");

      const std::array<Axis, dim> corners =
        lattice_axes(region, diameter, cube_edge);
      std::vector<Grain<dim>> grains;
      add_lattice<dim>(corners, cube_edge, diameter, grains);

      // Body centres exist only where there are cubes, i.e. two corner
      // layers in every direction.
      std::array<Axis, dim> centres = corners;
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (corners[d].n < 2)
            return grains;
          centres[d].n     = corners[d].n - 1;
          centres[d].first = corners[d].first + 0.5 * cube_edge;
        }
      add_lattice<dim>(centres, cube_edge, diameter, grains);
      return grains;
    }


    template <int dim>
    std::vector<Grain<dim>>
    random_pack(const BoundingBox<dim> &region,
                const SizeDistribution &distribution,
                const double            solid_fraction,
                const unsigned int      seed,
                const unsigned int      max_attempts_per_grain,
                const unsigned int      count)
    {
      if (count == 0 && !(solid_fraction > 0 && solid_fraction < 1))
        base::throw_invalid_parameter("grains/solid fraction",
                                      str(solid_fraction),
                                      "it must lie in (0, 1)");
      AssertThrow(max_attempts_per_grain > 0,
                  ExcMessage("random_pack() needs at least one insertion "
                             "attempt per grain."));

      const auto [lower, upper] = region.get_boundary_points();
      double     volume         = 1;
      double     min_side       = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        {
          volume *= upper[d] - lower[d];
          min_side = std::min(min_side, upper[d] - lower[d]);
        }
      AssertThrow(min_side > 0,
                  ExcMessage("The random pack region " + str(lower) + " - " +
                             str(upper) + " is empty."));
      if (distribution.min_diameter() > min_side)
        base::throw_invalid_parameter(
          distribution.kind() == SizeDistribution::Kind::constant ?
            "grains/diameter" :
            "grains/min diameter",
          str(distribution.min_diameter()),
          "the grains must fit in the random pack region, whose smallest "
          "side is " + str(min_side) + " m");

      std::mt19937 rng(seed);

      // Draw the sample first: its volume fixes the count, its largest
      // diameter the cell size.
      const double        target = solid_fraction * volume;
      std::vector<double> diameters;
      double              drawn = 0;
      while (count > 0 ? diameters.size() < count : drawn < target)
        {
          const double d = distribution.draw(rng);
          if (d > min_side)
            base::throw_invalid_parameter(
              "grains/max diameter",
              std::isfinite(distribution.max_diameter()) ?
                str(distribution.max_diameter()) :
                "0 (no upper bound)",
              "a drawn diameter " + str(d) + " m does not fit in the random "
              "pack region, whose smallest side is " + str(min_side) +
                " m; set a max diameter below that");
          diameters.push_back(d);
          drawn += ball_measure<dim>(0.5 * d);
          if (diameters.size() > max_grains)
            base::throw_invalid_parameter(
              "grains/solid fraction",
              str(solid_fraction),
              "the random pack would need more than " + str(max_grains) +
                " grains; check the units (m) of the diameters and the "
                "region");
        }
      std::sort(diameters.begin(), diameters.end(), std::greater<double>());

      std::vector<Grain<dim>> grains;
      grains.reserve(diameters.size());
      CellList<dim> cells(region, diameters.front(), diameters.size());
      double        placed = 0;
      for (const double diameter : diameters)
        {
          const double r = 0.5 * diameter;
          Grain<dim>   g;
          g.radius    = r;
          bool found  = false;
          for (unsigned int attempt = 0;
               attempt < max_attempts_per_grain && !found;
               ++attempt)
            {
              for (unsigned int d = 0; d < dim; ++d)
                g.center[d] = lower[d] + r +
                              (upper[d] - lower[d] - diameter) * uniform01(rng);
              found = !cells.any_near(g.center, [&](const unsigned int j) {
                const double s = r + grains[j].radius;
                return g.center.distance_square(grains[j].center) < s * s;
              });
            }
          AssertThrow(
            found,
            ExcMessage(
              "Random pack: grain " + std::to_string(grains.size() + 1) +
              " of " + std::to_string(diameters.size()) + " (diameter " +
              str(diameter) + " m) found no free place in " +
              std::to_string(max_attempts_per_grain) +
              " attempts at a solid fraction of " + str(placed / volume) +
              " (target " + str(solid_fraction) +
              "). Random sequential insertion jams near 0.38 in 3D (about "
              "0.55 for discs in 2D), lower near walls and for wide size "
              "ranges; lower \"grains/solid fraction\" or use a lattice "
              "(grains/source = simple cubic or bcc)."));
          cells.insert(grains.size(), g.center);
          grains.push_back(g);
          placed += g.measure();
        }
      return grains;
    }


    template <int dim>
    void
    check_grains(const std::vector<Grain<dim>> &grains,
                 const BoundingBox<dim>        &domain,
                 const std::string             &where,
                 const double                   max_overlap_ratio)
    {
      double max_diameter = 0;
      for (unsigned int i = 0; i < grains.size(); ++i)
        {
          const Grain<dim> &g = grains[i];
          AssertThrow(g.radius > 0 && std::isfinite(g.radius),
                      ExcMessage(where + ": grain " + std::to_string(i + 1) +
                                 " (counting from 1, centre " +
                                 str(g.center) + ") has radius " +
                                 str(g.radius) + "; radii must be > 0 m."));
          AssertThrow(domain.point_inside(g.center, 1e-12),
                      ExcMessage(
                        where + ": grain " + std::to_string(i + 1) +
                        " (counting from 1) has its centre " + str(g.center) +
                        " outside the domain " +
                        str(domain.get_boundary_points().first) + " - " +
                        str(domain.get_boundary_points().second) + "."));
          max_diameter = std::max(max_diameter, g.diameter());
        }
      if (grains.size() < 2)
        return;

      CellList<dim> cells(domain, max_diameter, grains.size());
      for (unsigned int i = 0; i < grains.size(); ++i)
        {
          const Grain<dim> &g = grains[i];
          unsigned int      other = 0;
          const bool        overlap =
            cells.any_near(g.center, [&](const unsigned int j) {
              const double sum   = g.radius + grains[j].radius;
              const double r_eff = g.radius * grains[j].radius / sum;
              const double s =
                sum - std::max(sum * overlap_tolerance, max_overlap_ratio * r_eff);
              other = j;
              return g.center.distance_square(grains[j].center) < s * s;
            });
          if (overlap)
            {
              const Grain<dim> &h = grains[other];
              const double      distance = g.center.distance(h.center);
              AssertThrow(false,
                          ExcMessage(
                            where + ": grains " + std::to_string(other + 1) +
                            " and " + std::to_string(i + 1) +
                            " (counting from 1) overlap by " +
                            str(g.radius + h.radius - distance) +
                            " m: centres " + str(h.center) + " and " +
                            str(g.center) + ", radii " + str(h.radius) +
                            " and " + str(g.radius) + " m; that is " +
                            str((g.radius + h.radius - distance) /
                                (g.radius * h.radius / (g.radius + h.radius))) +
                            " R*, more than grains/max overlap ratio = " +
                            str(max_overlap_ratio) +
                            " allows (settled DEM packs touch with overlaps "
                            "of a few % of R*)."));
            }
          cells.insert(i, g.center);
        }
    }


    template SizeDistribution
    make_size_distribution(const GrainParameters<2> &);
    template SizeDistribution
    make_size_distribution(const GrainParameters<3> &);

    template std::vector<Grain<2>>
    simple_cubic_array(const BoundingBox<2> &, const double, const double);
    template std::vector<Grain<3>>
    simple_cubic_array(const BoundingBox<3> &, const double, const double);

    template std::vector<Grain<2>>
    bcc_array(const BoundingBox<2> &, const double, const double);
    template std::vector<Grain<3>>
    bcc_array(const BoundingBox<3> &, const double, const double);

    template std::vector<Grain<2>>
    random_pack(const BoundingBox<2> &,
                const SizeDistribution &,
                const double,
                const unsigned int,
                const unsigned int,
                const unsigned int);
    template std::vector<Grain<3>>
    random_pack(const BoundingBox<3> &,
                const SizeDistribution &,
                const double,
                const unsigned int,
                const unsigned int,
                const unsigned int);

    template void
    check_grains(const std::vector<Grain<2>> &,
                 const BoundingBox<2> &,
                 const std::string &,
                 const double);
    template void
    check_grains(const std::vector<Grain<3>> &,
                 const BoundingBox<3> &,
                 const std::string &,
                 const double);

    namespace
    {
      template <int dim>
      std::vector<Grain<dim>>
      parse_grain_list(const std::string &text)
      {
        std::vector<Grain<dim>> grains;
        for (const std::string &item :
             Utilities::split_string_list(text, ';'))
          {
            std::vector<double> v;
            try
              {
                for (const auto &x : Utilities::split_string_list(item, ','))
                  v.push_back(Utilities::string_to_double(x));
              }
            catch (...)
              {
                v.clear();
              }
            if (v.size() != dim + 1)
              base::throw_invalid_parameter(
                "grains/list",
                item,
                "each grain is 'x, y, " + std::string(dim == 3 ? "z, " : "") +
                  "radius' with numbers");
            Grain<dim> g;
            for (unsigned int d = 0; d < dim; ++d)
              g.center[d] = v[d];
            g.radius = v[dim];
            if (!(g.radius > 0))
              base::throw_invalid_parameter("grains/list",
                                            item,
                                            "the radius must be > 0 m");
            grains.push_back(g);
          }
        return grains;
      }
    } // namespace


    template <int dim>
    void
    set_initial_velocities(std::vector<Grain<dim>>    &grains,
                           const GrainParameters<dim> &p)
    {
      for (auto &g : grains)
        {
          g.velocity         = p.velocity;
          g.angular_velocity = p.angular_velocity;
        }
    }


    template <int dim>
    std::vector<Grain<dim>>
    create_grains(const GrainParameters<dim> &p,
                  const BoundingBox<dim>     &domain)
    {
      using S = typename GrainParameters<dim>::Source;
      AssertThrow(p.source != S::file,
                  ExcMessage("Internal error: pack files (grains/source = "
                             "file) are read by io::create_scene_grains()."));
      const BoundingBox<dim> region =
        p.region_is_domain ?
          domain :
          BoundingBox<dim>(std::make_pair(p.region_lower, p.region_upper));

      std::vector<Grain<dim>> grains;
      switch (p.source)
        {
          case S::none:
          case S::file:
            break;
          case S::list:
            grains = parse_grain_list<dim>(p.list);
            // Listed packs come from users: refuse overlaps and grains
            // outside the domain before anything is built on them.
            check_grains(grains, domain, "grains/list", p.max_overlap_ratio);
            break;
          case S::simple_cubic:
            grains = simple_cubic_array(region, p.diameter, p.lattice_spacing);
            break;
          case S::bcc:
            grains = bcc_array(region, p.diameter, p.lattice_spacing);
            break;
          case S::random:
            grains = random_pack(region,
                                 make_size_distribution(p),
                                 p.solid_fraction,
                                 p.seed,
                                 100000,
                                 p.count);
            break;
        }
      set_initial_velocities(grains, p);
      return grains;
    }

    template void
    set_initial_velocities(std::vector<Grain<2>> &, const GrainParameters<2> &);
    template void
    set_initial_velocities(std::vector<Grain<3>> &, const GrainParameters<3> &);
    template std::vector<Grain<2>>
    create_grains(const GrainParameters<2> &, const BoundingBox<2> &);
    template std::vector<Grain<3>>
    create_grains(const GrainParameters<3> &, const BoundingBox<3> &);
  } // namespace dem
} // namespace softsand
