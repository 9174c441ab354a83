#include <softsand/coupling/grain_mesh_refinement.h>

#include <deal.II/base/mpi.h>

namespace softsand
{
  namespace coupling
  {
    template <int dim>
    double
    min_cell_edge(const parallel::distributed::Triangulation<dim> &tria)
    {
      double h = std::numeric_limits<double>::max();
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          h = std::min(h, cell->minimum_vertex_distance());
      return Utilities::MPI::min(h, tria.get_communicator());
    }


    template <int dim>
    unsigned int
    refine_around_grains(parallel::distributed::Triangulation<dim> &tria,
                         const GrainLocator<dim>                   &locator,
                         const double       target_cell_size,
                         const unsigned int max_level,
                         const bool         uniform)
    {
      unsigned int sweeps = 0;
      while (true)
        {
          unsigned int n_flagged = 0;
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() &&
                cell->level() < int(max_level) &&
                cell->minimum_vertex_distance() > target_cell_size * (1 + 1e-10))
              {
                int  grain = -1;
                bool refine = uniform;
                if (!refine)
                  refine = locator.classify_box(cell->bounding_box(), grain) ==
                           GrainLocator<dim>::BoxRelation::cut;
                if (refine)
                  {
                    cell->set_refine_flag();
                    ++n_flagged;
                  }
              }
          if (Utilities::MPI::sum(n_flagged, tria.get_communicator()) == 0)
            break;
          tria.execute_coarsening_and_refinement();
          ++sweeps;
        }
      return sweeps;
    }

    template <int dim>
    bool
    flag_cells_around_grains(parallel::distributed::Triangulation<dim> &tria,
                             const GrainLocator<dim>                   &locator,
                             const double       target_cell_size,
                             const double       margin,
                             const unsigned int base_level,
                             const unsigned int max_level)
    {
      const auto near_surface = [&](const BoundingBox<dim> &cell_box) {
        BoundingBox<dim> box = cell_box;
        box.extend(margin);
        int grain = -1;
        return locator.classify_box(box, grain) ==
               GrainLocator<dim>::BoxRelation::cut;
      };
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->clear_refine_flag();
            cell->clear_coarsen_flag();
            if (near_surface(cell->bounding_box()))
              {
                if (cell->level() < int(max_level) &&
                    cell->minimum_vertex_distance() >
                      target_cell_size * (1 + 1e-10))
                  cell->set_refine_flag();
              }
            // The parent must stay coarse after coarsening, or the next
            // sweep would refine it again.
            else if (cell->level() > int(base_level) &&
                     !near_surface(cell->parent()->bounding_box()))
              cell->set_coarsen_flag();
          }
      tria.prepare_coarsening_and_refinement();
      unsigned int n_flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() &&
            (cell->refine_flag_set() || cell->coarsen_flag_set()))
          ++n_flagged;
      return Utilities::MPI::sum(n_flagged, tria.get_communicator()) > 0;
    }

    template bool
    flag_cells_around_grains(parallel::distributed::Triangulation<2> &,
                             const GrainLocator<2> &,
                             const double,
                             const double,
                             const unsigned int,
                             const unsigned int);
    template bool
    flag_cells_around_grains(parallel::distributed::Triangulation<3> &,
                             const GrainLocator<3> &,
                             const double,
                             const double,
                             const unsigned int,
                             const unsigned int);
    template unsigned int
    refine_around_grains(parallel::distributed::Triangulation<2> &,
                         const GrainLocator<2> &,
                         const double,
                         const unsigned int,
                         const bool);
    template unsigned int
    refine_around_grains(parallel::distributed::Triangulation<3> &,
                         const GrainLocator<3> &,
                         const double,
                         const unsigned int,
                         const bool);
    template double
    min_cell_edge(const parallel::distributed::Triangulation<2> &);
    template double
    min_cell_edge(const parallel::distributed::Triangulation<3> &);
  } // namespace coupling
} // namespace softsand
