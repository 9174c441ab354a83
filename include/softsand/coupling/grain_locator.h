#ifndef softsand_coupling_grain_locator_h
#define softsand_coupling_grain_locator_h

#include <deal.II/base/bounding_box.h>

#include <softsand/dem/grain.h>

#include <vector>

namespace softsand
{
  namespace coupling
  {
    using namespace dealii;

    /**
     * Finds the grains near a point or a box in O(1) with a uniform bin grid
     * (bin edge = largest grain diameter), so that evaluating the void
     * fraction on a mesh with many grains costs O(cells), not O(cells x
     * grains).
     */
    template <int dim>
    class GrainLocator
    {
    public:
      enum class BoxRelation
      {
        outside_all,
        inside_one,
        cut
      };

      explicit GrainLocator(const std::vector<dem::Grain<dim>> &grains);

      /// Index of the grain containing @p x (the deepest if several overlap),
      /// or -1.
      int
      containing_grain(const Point<dim> &x) const;

      /// As above for grains grown by @p inflation (m): the deepest grain
      /// with |x - centre| <= radius + inflation, or -1.
      int
      containing_grain(const Point<dim> &x, const double inflation) const;

      /// containing_grain(x, inflation) among @p candidates only: the
      /// grains_near_box() of a box that holds @p x grown by @p inflation
      /// (one search per cell instead of one per point).
      int
      containing_grain(const Point<dim>                &x,
                       const double                     inflation,
                       const std::vector<unsigned int> &candidates) const;

      /// Whether the box lies outside all grains, wholly inside one grain
      /// (then @p grain_index is set), or is cut by a grain surface.
      BoxRelation
      classify_box(const BoundingBox<dim> &box, int &grain_index) const;

      /// As above, and @p near holds the grains_near_box() of @p box.
      BoxRelation
      classify_box(const BoundingBox<dim>    &box,
                   int                       &grain_index,
                   std::vector<unsigned int> &near) const;

      /// Indices of grains whose bounding box meets @p box.
      void
      grains_near_box(const BoundingBox<dim> &box,
                      std::vector<unsigned int> &indices) const;

      const std::vector<dem::Grain<dim>> &
      grains() const
      {
        return grain_list;
      }

      double
      min_diameter() const
      {
        return min_grain_diameter;
      }

    private:
      const std::vector<dem::Grain<dim>> &grain_list;
      Point<dim>                          origin;
      double                              bin_size = 1;
      std::array<int, dim>                n_bins{};
      std::vector<std::vector<unsigned int>> bins;
      double                              min_grain_diameter = 0;
      double                              max_radius         = 0;

      std::array<int, dim>
      bin_of(const Point<dim> &x) const;
      unsigned int
      flat_index(const std::array<int, dim> &b) const;
    };
  } // namespace coupling
} // namespace softsand

#endif
