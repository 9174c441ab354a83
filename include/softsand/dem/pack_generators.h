#ifndef softsand_dem_pack_generators_h
#define softsand_dem_pack_generators_h

#include <deal.II/base/bounding_box.h>

#include <softsand/dem/grain.h>
#include <softsand/dem/grain_parameters.h>

#include <random>
#include <string>
#include <vector>

namespace softsand
{
  namespace dem
  {
    /**
     * Grain diameter distribution of a random pack. Draws use only
     * std::mt19937 (whose output the standard fixes) and their own uniform
     * and normal transforms, so that a pack is the same for a given seed on
     * every platform and standard library.
     *
     * The named constructors check their arguments and name the matching
     * "grains/..." parameter in their messages.
     */
    class SizeDistribution
    {
    public:
      enum class Kind
      {
        constant,
        uniform,
        truncated_normal,
        lognormal,
        discrete
      };

      /// All grains of diameter @p diameter.
      static SizeDistribution
      constant(const double diameter);

      /// Diameters uniform in [@p min_diameter, @p max_diameter].
      static SizeDistribution
      uniform(const double min_diameter, const double max_diameter);

      /// Normal(@p mean, @p sd) restricted to [@p min_diameter,
      /// @p max_diameter] by rejection; the range must be nonempty and
      /// positive so that no grain degenerates to a point.
      static SizeDistribution
      truncated_normal(const double mean,
                       const double sd,
                       const double min_diameter,
                       const double max_diameter);

      /// Lognormal whose diameter (not its logarithm) has mean @p mean and
      /// standard deviation @p sd, because that is what sieve curves report.
      /// Truncated to [@p min_diameter, @p max_diameter] if
      /// @p max_diameter > 0, else unbounded above.
      static SizeDistribution
      lognormal(const double mean,
                const double sd,
                const double min_diameter,
                const double max_diameter);

      /// A few sizes @p diameters with mass (volume) fractions
      /// @p mass_fractions, as LIGGGHTS' particledistribution/discrete.
      static SizeDistribution
      discrete(const std::vector<double> &diameters,
               const std::vector<double> &mass_fractions);

      /// One diameter (m).
      double
      draw(std::mt19937 &rng) const;

      Kind
      kind() const
      {
        return type;
      }

      /// Smallest diameter that draw() can return (m).
      double
      min_diameter() const
      {
        return lower;
      }

      /// Largest diameter that draw() can return (m); infinite for an
      /// untruncated lognormal.
      double
      max_diameter() const
      {
        return upper;
      }

    private:
      SizeDistribution(const Kind   kind,
                       const double a,
                       const double b,
                       const double lower,
                       const double upper);

      Kind type;
      /// constant: diameter; normal: mean, sd; lognormal: mu, sigma of log d.
      double a, b;
      double lower, upper;
      /// discrete: the sizes and the cumulative number probabilities.
      std::vector<double> sizes, cumulative;
    };

    /// The distribution chosen by "grains/size distribution" and its
    /// "min/max/mean diameter", "diameter standard deviation" entries.
    template <int dim>
    SizeDistribution
    make_size_distribution(const GrainParameters<dim> &parameters);

    /// Grains on a simple cubic lattice of centre distance @p spacing: one
    /// grain at the centre of each lattice cell lying wholly in @p region
    /// (at least one per direction, centred if the region is thinner than a
    /// cell, for single-layer packs).
    template <int dim>
    std::vector<Grain<dim>>
    simple_cubic_array(const BoundingBox<dim> &region,
                       const double            diameter,
                       const double            spacing);

    /// Body-centred cubic lattice: the simple cubic array of spacing
    /// @p cube_edge plus one grain at the centre of each cube that these
    /// corner grains span.
    template <int dim>
    std::vector<Grain<dim>>
    bcc_array(const BoundingBox<dim> &region,
              const double            diameter,
              const double            cube_edge);

    /**
     * Random sequential insertion of non-overlapping grains lying wholly in
     * @p region until their volume (area in 2D) reaches @p solid_fraction of
     * the region's. The diameters are drawn first and inserted largest
     * first: the set of sizes is then exactly the drawn sample (no bias
     * towards small grains that still fit), and the reachable fraction is
     * higher. Overlap tests use a uniform cell list, so the cost is O(N).
     * If @p count > 0, exactly that many grains are drawn and
     * @p solid_fraction is ignored.
     * Stops with a message if a grain finds no place in
     * @p max_attempts_per_grain tries (the pack has jammed).
     */
    template <int dim>
    std::vector<Grain<dim>>
    random_pack(const BoundingBox<dim> &region,
                const SizeDistribution &distribution,
                const double            solid_fraction,
                const unsigned int      seed,
                const unsigned int      max_attempts_per_grain,
                const unsigned int      count = 0);

    /**
     * Check that every grain has a positive radius and its centre in
     * @p domain, and that no two grains overlap by more than
     * @p max_overlap_ratio times their effective radius R* (and at least
     * 1e-9 of the sum of their radii), with a cell list in O(N). Packs from files or lists are
     * the usual culprits; @p where names the source in the message
     * (e.g. "grains/file = pack.txt").
     */
    template <int dim>
    void
    check_grains(const std::vector<Grain<dim>> &grains,
                 const BoundingBox<dim>        &domain,
                 const std::string             &where,
                 const double                   max_overlap_ratio = 0);

    /// Give every grain the velocity and angular velocity of the grains
    /// subsection.
    template <int dim>
    void
    set_initial_velocities(std::vector<Grain<dim>>    &grains,
                           const GrainParameters<dim> &parameters);

    /**
     * Build the grains of a generated or listed source (none, list,
     * lattices, random packs); @p domain is the fluid box (the default
     * region of lattices and random packs). Pack files are read by
     * io::create_scene_grains().
     */
    template <int dim>
    std::vector<Grain<dim>>
    create_grains(const GrainParameters<dim> &parameters,
                  const BoundingBox<dim>     &domain);
  } // namespace dem
} // namespace softsand

#endif
