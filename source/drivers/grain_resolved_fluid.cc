#include <softsand/base/parameter_tools.h>
#include <softsand/coupling/grain_mesh_refinement.h>
#include <softsand/drivers/fluid_columns.h>
#include <softsand/drivers/grain_resolved_fluid.h>
#include <softsand/drivers/scene_setup.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    template <int dim>
    GrainResolvedFluid<dim>::GrainResolvedFluid(
      const core::Parameters<dim> &parameters,
      const MPI_Comm               comm,
      ConditionalOStream          &progress,
      TimerOutput                 &timer)
      : parameters(parameters)
      , mpi_communicator(comm)
      , progress(progress)
      , timer(timer)
      , mesh(comm,
             typename Triangulation<dim>::MeshSmoothing(
               Triangulation<dim>::limit_level_difference_at_vertices))
      , solids(make_solid_field())
      , columns(make_fluid_columns(parameters, comm))
    {}


    template <int dim>
    std::unique_ptr<coupling::GrainSolidField<dim>>
    GrainResolvedFluid<dim>::make_solid_field() const
    {
      auto field = std::make_unique<coupling::GrainSolidField<dim>>(
        grain_list, parameters.void_fraction);
      if (parameters.hybrid_model.enabled)
        {
          // Without an inlet region the radius is 0 (checked when
          // parsed): every grain porous, whatever the axis.
          const auto &inlet = parameters.boundary_conditions.inlet_region();
          Tensor<1, dim> axis;
          axis[dim - 1] = 1;
          field->set_porous_zone(
            parameters.hybrid_model,
            inlet.enabled() ? inlet.center : Point<dim>(),
            inlet.enabled() ? inlet.axis : axis,
            BoundingBox<dim>(std::make_pair(parameters.mesh.lower_corner,
                                            parameters.mesh.upper_corner)));
        }
      return field;
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::set_grains(std::vector<dem::Grain<dim>> new_grains)
    {
      grain_list = std::move(new_grains);
      solids     = make_solid_field();
      if (navier_stokes)
        navier_stokes->set_solid_field(grain_list.empty() ? nullptr :
                                                            solids.get());
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::weight_cut_cells(const double extra_weight)
    {
      mesh.signals.weight.connect(
        [this, extra_weight](
          const typename Triangulation<dim>::cell_iterator &cell,
          const typename Triangulation<dim>::CellStatus) -> unsigned int {
          int grain = -1;
          return solids->refinement_locator().classify_box(
                   cell->bounding_box(), grain) ==
                     coupling::GrainLocator<dim>::BoxRelation::cut ?
                   static_cast<unsigned int>(std::round(1 + extra_weight)) :
                   1u;
        });
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::make_mesh(const bool refine,
                                       const bool follow_grains)
    {
      {
        TimerOutput::Scope t(timer, "mesh");
        const auto        &m = parameters.mesh;
        const bool         resolve_grains =
          !grain_list.empty() && m.cells_per_diameter > 0;
        // Before the mesh grows: a mesh too large for the machine is
        // refused with the entry that makes it so.
        if (refine)
          check_memory_estimate(parameters,
                                grain_list,
                                resolve_grains ?
                                  solids->locator().min_diameter() :
                                  0.,
                                mpi_communicator);
        make_domain_mesh(mesh,
                      m,
                      resolve_grains ? solids->locator().min_diameter() : 0.);
        if (!refine)
          return;
        mesh.refine_global(m.global_refinements);
        if (resolve_grains && follow_grains)
          adapt_to_grains(false);
        else if (resolve_grains)
          coupling::refine_around_grains(mesh,
                                         solids->refinement_locator(),
                                         solids->locator().min_diameter() /
                                           m.cells_per_diameter,
                                         m.max_refinement_level,
                                         m.uniform_refinement);
      }
      // Outside the timed section: a stop here is reported cleanly.
      check_resolution();
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::check_resolution() const
    {
      if (grain_list.empty() || parameters.mesh.allow_unresolved_grains)
        return;
      // A grain across fewer than two cells is no solid body on the mesh:
      // a 1 mm sphere in one 10 mm cell gave a drag coefficient of 1.6e18.
      // The hybrid model's porous grains need no resolution.
      const auto &resolved = solids->refinement_locator();
      if (resolved.grains().empty())
        return;
      const double finest    = coupling::min_cell_edge(mesh);
      const double d_min     = resolved.min_diameter();
      const double per_grain = d_min / finest;
      const auto three_digits = [](const double x) {
        std::ostringstream s;
        s << std::setprecision(3) << x;
        return s.str();
      };
      if (per_grain < 2)
        base::throw_invalid_parameter(
          "mesh/cells per diameter",
          three_digits(parameters.mesh.cells_per_diameter),
          "the finest cells are " + three_digits(finest) +
            " m wide and the smallest grain " + three_digits(d_min) +
            " m across: " + three_digits(per_grain) +
            " cells, fewer than 2, so the grains are not resolved. Refine "
            "(mesh/cells per diameter >= 2, or with 0 more mesh/global "
            "refinements or coarse cells), or set mesh/allow unresolved "
            "grains = true to run the grains as a blur of solid fraction");
    }


    template <int dim>
    unsigned int
    GrainResolvedFluid<dim>::adapt_to_grains(const bool transfer)
    {
      TimerOutput::Scope t(timer, "mesh: follow grains");
      const auto        &m      = parameters.mesh;
      unsigned int       sweeps = 0;
      if (!grain_list.empty() && m.cells_per_diameter > 0)
        {
          const double target =
            solids->locator().min_diameter() / m.cells_per_diameter;
          const double margin = parameters.coupling.readapt_fraction * target;
          // One sweep moves cells by one level; grains that moved less than
          // the margin need one. Bounded in case p4est's smoothing undoes
          // a flag each time.
          for (; sweeps < 2 * m.max_refinement_level + 2; ++sweeps)
            {
              if (!coupling::flag_cells_around_grains(mesh,
                                                      solids->refinement_locator(),
                                                      target,
                                                      margin,
                                                      m.global_refinements,
                                                      m.max_refinement_level))
                break;
              if (transfer)
                navier_stokes->prepare_for_coarsening_and_refinement();
              mesh.execute_coarsening_and_refinement();
              if (transfer)
                navier_stokes->transfer_after_coarsening_and_refinement();
            }
        }
      adaptation_centers.resize(grain_list.size());
      for (unsigned int g = 0; g < grain_list.size(); ++g)
        adaptation_centers[g] = grain_list[g].center;
      return sweeps;
    }


    template <int dim>
    double
    GrainResolvedFluid<dim>::max_displacement_since_adaptation() const
    {
      // Grains that left the domain change the list: adapt anew.
      if (adaptation_centers.size() != grain_list.size())
        return std::numeric_limits<double>::max();
      double largest = 0;
      for (unsigned int g = 0; g < grain_list.size(); ++g)
        largest = std::max(largest,
                           grain_list[g].center.distance(adaptation_centers[g]));
      return largest;
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::create_solver(const bool moving_solids)
    {
      navier_stokes = make_fluid_solver(mesh, parameters, progress, timer);
      navier_stokes->set_moving_solids(moving_solids);
      navier_stokes->set_solid_field(grain_list.empty() ? nullptr :
                                                          solids.get());
      if (parameters.output.write_vtu)
        field_output = std::make_unique<io::FieldOutput<dim>>(
          parameters.output.directory, "solution");
    }


    template <int dim>
    postprocess::Columns
    GrainResolvedFluid<dim>::postprocess(const unsigned int step,
                                         const double       time,
                                         const bool         write_files)
    {
      TimerOutput::Scope t(timer, "postprocess");
      reaction_forces = coupling::GrainForces<dim>();
      eq7_forces      = coupling::GrainForces<dim>();
      if (!grain_list.empty())
        {
          TimerOutput::Scope t(timer, "postprocess: grain forces");
          reaction_forces = coupling::compute_grain_forces(
            *navier_stokes,
            grain_list,
            coupling::ForceModel::penalization_reaction,
            mpi_communicator);
          if (solids->porous_zone() != nullptr)
            coupling::add_porous_grain_forces(*navier_stokes,
                                              grain_list,
                                              *solids,
                                              parameters.fluid.viscosity,
                                              parameters.fluid.density,
                                              reaction_forces,
                                              mpi_communicator);
          if (parameters.postprocessing.eq7_forces ||
              parameters.coupling.paper_force)
            eq7_forces = coupling::compute_grain_forces(
              *navier_stokes,
              grain_list,
              coupling::ForceModel::stress_divergence,
              mpi_communicator);
        }
      pores.reset();
      if (!grain_list.empty())
        {
          TimerOutput::Scope t(timer, "postprocess: pore connectivity");
          // The paper's cell-average penalization closes a cell by any
          // covered part; the other rules by most of it.
          postprocess::OpenCellRule rule;
          rule.brinkman =
            parameters.fluid.solid_model ==
              fluid::FluidParameters::SolidModel::penalization &&
            parameters.void_fraction.model ==
              coupling::VoidFractionParameters::Model::cell_average;
          rule.density   = parameters.fluid.density;
          rule.viscosity = parameters.fluid.viscosity;
          rule.theta     = parameters.fluid.theta;
          rule.time_step = parameters.simulation_control.time_step;
          pores          = std::make_unique<postprocess::PoreConnectivity>(
            mesh, *solids, parameters.boundary_conditions, rule);
        }
      const postprocess::FluidSnapshot<dim> snapshot{mesh,
                                                     *navier_stokes,
                                                     grain_list,
                                                     *solids,
                                                     reaction_forces,
                                                     eq7_forces,
                                                     step,
                                                     time,
                                                     write_files,
                                                     pores.get()};
      postprocess::Columns row;
      {
        TimerOutput::Scope t(timer, "postprocess: columns");
        for (const auto &source : columns)
          source->add_columns(snapshot, row);
        if (const auto *zone = solids->porous_zone())
          add_hybrid_columns(*zone, row);
      }
      if (write_files)
        {
          TimerOutput::Scope t(timer, "postprocess: files");
          write_fields(step, time);
          if (parameters.postprocessing.write_grain_forces &&
              !grain_list.empty())
            write_grain_forces();
        }
      return row;
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::add_hybrid_columns(
      const coupling::PorousZone<dim> &zone,
      postprocess::Columns            &row) const
    {
      // How much of the pack the hybrid model resolves: grains by volume
      // (their resolved shares), cells by count.
      double resolved_volume = 0, volume = 0;
      for (const auto &g : grain_list)
        {
          const double v = g.measure();
          volume += v;
          resolved_volume += (1. - zone.porous_share(g)) * v;
        }
      double porous_cells = 0;
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned() && zone.is_porous(*cell))
          porous_cells += 1;
      porous_cells = Utilities::MPI::sum(porous_cells, mpi_communicator);
      row["resolved_grain_fraction"] =
        volume > 0 ? resolved_volume / volume : 0.;
      row["porous_cell_fraction"] = porous_cells / mesh.n_global_active_cells();
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::write_initial_state(const double time)
    {
      TimerOutput::Scope t(timer, "postprocess: files");
      pores.reset();
      const coupling::GrainForces<dim>      no_forces;
      const postprocess::FluidSnapshot<dim> snapshot{mesh,
                                                     *navier_stokes,
                                                     grain_list,
                                                     *solids,
                                                     no_forces,
                                                     no_forces,
                                                     0,
                                                     time,
                                                     true,
                                                     nullptr};
      for (const auto &source : columns)
        source->write_initial_files(snapshot);
      write_fields(0, time);
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::write_fields(const unsigned int step,
                                          const double       time) const
    {
      if (!field_output)
        return;
      Vector<float> void_fraction(mesh.n_active_cells());
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            int g;
            void_fraction(cell->active_cell_index()) =
              1. - solids->cell_solid_fraction(*cell, g);
          }
      // 0: closed (grain), 1: open and joined to a reservoir, 2: a sealed
      // pocket.
      Vector<float> pore_space;
      if (pores)
        {
          pore_space.reinit(mesh.n_active_cells());
          for (const auto &cell : mesh.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                const unsigned int i = cell->active_cell_index();
                pore_space(i) = pores->connected(i) ? 1 : pores->sealed(i) ? 2 : 0;
              }
        }
      field_output->write(navier_stokes->get_dof_handler(),
                          navier_stokes->get_solution(),
                          void_fraction,
                          time,
                          step,
                          pores ? &pore_space : nullptr);
    }


    template <int dim>
    void
    GrainResolvedFluid<dim>::write_grain_forces() const
    {
      if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
        return;
      // Written aside and renamed: a reader never sees half a file.
      const std::string name = parameters.output.directory + "/grain_forces.txt";
      {
        std::ofstream out(name + ".tmp");
        const bool eq7 = !eq7_forces.force.empty();
        out << "# grain x y" << (dim == 3 ? " z" : "") << " radius fx fy"
            << (dim == 3 ? " fz" : "") << " tx ty tz";
        if (eq7)
          out << " eq7_fx eq7_fy" << (dim == 3 ? " eq7_fz" : "");
        out << '\n' << std::setprecision(10);
        for (unsigned int g = 0; g < grain_list.size(); ++g)
          {
            out << g << ' ' << grain_list[g].center << ' '
                << grain_list[g].radius << ' ' << reaction_forces.force[g]
                << ' ' << reaction_forces.torque[g];
            if (eq7)
              out << ' ' << eq7_forces.force[g];
            out << '\n';
          }
      }
      std::rename((name + ".tmp").c_str(), name.c_str());
    }

    template class GrainResolvedFluid<2>;
    template class GrainResolvedFluid<3>;
  } // namespace drivers
} // namespace softsand
