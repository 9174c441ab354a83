#include <softsand/dem/pack_generators.h>
#include <softsand/io/grain_file.h>
#include <softsand/io/scene_grains.h>

namespace softsand
{
  namespace io
  {
    template <int dim>
    std::vector<dem::Grain<dim>>
    create_scene_grains(const dem::GrainParameters<dim> &p,
                        const BoundingBox<dim>          &domain)
    {
      if (p.source != dem::GrainParameters<dim>::Source::file)
        return dem::create_grains(p, domain);
      std::vector<dem::Grain<dim>> grains = read_grain_file<dim>(p.file);
      // Loaded packs come from users: refuse overlaps and grains outside
      // the domain before anything is built on them.
      dem::check_grains(grains,
                        domain,
                        "grains/file = " + p.file,
                        p.max_overlap_ratio);
      if (p.zero_file_velocities)
        dem::set_initial_velocities(grains, p);
      return grains;
    }

    template std::vector<dem::Grain<2>>
    create_scene_grains(const dem::GrainParameters<2> &, const BoundingBox<2> &);
    template std::vector<dem::Grain<3>>
    create_scene_grains(const dem::GrainParameters<3> &, const BoundingBox<3> &);
  } // namespace io
} // namespace softsand
