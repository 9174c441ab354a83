#include <softsand/io/field_output.h>

#include <deal.II/base/data_out_base.h>

#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <cstdio>
#include <fstream>

namespace softsand
{
  namespace io
  {
    template <int dim>
    FieldOutput<dim>::FieldOutput(const std::string &directory,
                                  const std::string &base_name)
      : series(directory, base_name)
    {}


    template <int dim>
    void
    FieldOutput<dim>::write(
      const DoFHandler<dim>                    &dof_handler,
      const TrilinosWrappers::MPI::BlockVector &solution,
      const Vector<float>                      &cell_void_fraction,
      const double                              time,
      const unsigned int                        step,
      const Vector<float>                      *pore_space)
    {
      const MPI_Comm comm = dof_handler.get_communicator();
      std::vector<std::string> names(dim, "velocity");
      names.emplace_back("pressure");
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
        interpretation(dim,
                       DataComponentInterpretation::component_is_part_of_vector);
      interpretation.push_back(DataComponentInterpretation::component_is_scalar);

      DataOut<dim> data_out;
      data_out.attach_dof_handler(dof_handler);
      data_out.add_data_vector(solution,
                               names,
                               DataOut<dim>::type_dof_data,
                               interpretation);
      data_out.add_data_vector(cell_void_fraction, "void_fraction");
      if (pore_space != nullptr)
        data_out.add_data_vector(*pore_space, "pore_space");

      const auto &tria = dof_handler.get_triangulation();
      Vector<float> level(tria.n_active_cells()), subdomain(level.size());
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            level(cell->active_cell_index())     = cell->level();
            subdomain(cell->active_cell_index()) = cell->subdomain_id();
          }
      data_out.add_data_vector(level, "refinement_level");
      data_out.add_data_vector(subdomain, "subdomain");
      data_out.build_patches(2);

      DataOutBase::VtkFlags flags;
      flags.time                     = time;
      flags.write_higher_order_cells = true;
      data_out.set_flags(flags);

      series.write_step(data_out, step, time, comm);
    }

    template class FieldOutput<2>;
    template class FieldOutput<3>;
  } // namespace io
} // namespace softsand
