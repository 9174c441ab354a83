#ifndef softsand_io_scene_grains_h
#define softsand_io_scene_grains_h

#include <deal.II/base/bounding_box.h>

#include <softsand/dem/grain.h>
#include <softsand/dem/grain_parameters.h>

#include <vector>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    /// The grains of a scene: read from its pack file (grains/source =
    /// file; checked for overlaps and grains outside @p domain) or built by
    /// dem::create_grains(). @p domain is the fluid box.
    template <int dim>
    std::vector<dem::Grain<dim>>
    create_scene_grains(const dem::GrainParameters<dim> &parameters,
                        const BoundingBox<dim>          &domain);
  } // namespace io
} // namespace softsand

#endif
