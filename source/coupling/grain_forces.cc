#include <softsand/coupling/grain_forces.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

namespace softsand
{
  namespace coupling
  {
    template <int dim>
    Tensor<1, dim>
    GrainForces<dim>::total_force() const
    {
      Tensor<1, dim> sum;
      for (const auto &f : force)
        sum += f;
      return sum;
    }


    template <int dim>
    GrainForces<dim>
    compute_grain_forces(const fluid::PenalizedNavierStokes<dim> &fluid,
                         const std::vector<dem::Grain<dim>>      &grains,
                         const ForceModel                          model,
                         const MPI_Comm                            comm)
    {
      // Force and torque components per grain in one flat array so that a
      // single reduction sums them over the ranks.
      const unsigned int  stride = dim + 3;
      std::vector<double> local(stride * grains.size(), 0.);
      const auto          add = [&](const int               g,
                           const Point<dim>     &x,
                           const Tensor<1, dim> &f) {
        double *entry = &local[stride * g];
        for (unsigned int d = 0; d < dim; ++d)
          entry[d] += f[d];
        const Tensor<1, dim> r = x - grains[g].center;
        if constexpr (dim == 2)
          entry[dim + 2] += r[0] * f[1] - r[1] * f[0];
        else
          {
            entry[dim + 0] += r[1] * f[2] - r[2] * f[1];
            entry[dim + 1] += r[2] * f[0] - r[0] * f[2];
            entry[dim + 2] += r[0] * f[1] - r[1] * f[0];
          }
      };
      if (model == ForceModel::penalization_reaction)
        fluid.for_each_solid_reaction(add);
      else
        fluid.for_each_solid_stress_divergence(add);

      std::vector<double> global(local.size());
      Utilities::MPI::sum(local, comm, global);

      GrainForces<dim> result;
      result.force.resize(grains.size());
      result.torque.resize(grains.size());
      for (unsigned int g = 0; g < grains.size(); ++g)
        {
          for (unsigned int d = 0; d < dim; ++d)
            result.force[g][d] = global[stride * g + d];
          for (unsigned int d = 0; d < 3; ++d)
            result.torque[g][d] = global[stride * g + dim + d];
        }
      return result;
    }

    template <int dim>
    void
    add_porous_grain_forces(const fluid::PenalizedNavierStokes<dim> &fluid,
                            const std::vector<dem::Grain<dim>>      &grains,
                            const GrainSolidField<dim>              &solids,
                            const double                   viscosity,
                            const double                   density,
                            GrainForces<dim>              &forces,
                            const MPI_Comm                 comm)
    {
      const PorousZone<dim> *zone = solids.porous_zone();
      if (zone == nullptr)
        return;
      // Where each grain's porous share is evaluated: its centre when that
      // lies in the porous zone, else the middle of the share beyond the
      // zone's surface, along the direction away from the axis.
      // (A copy of the grains with those points as centres: its locator
      // finds them by cell.)
      std::vector<double>          share(grains.size());
      std::vector<dem::Grain<dim>> evaluated(grains);
      for (unsigned int g = 0; g < grains.size(); ++g)
        {
          share[g] = zone->porous_share(grains[g]);
          const Tensor<1, dim> radial = zone->radial_vector(grains[g].center);
          const double         r      = radial.norm();
          if (share[g] > 0 && r < zone->resolved_radius() && r > 0)
            {
              const double target =
                0.5 * (zone->resolved_radius() + r + grains[g].radius);
              evaluated[g].center += (target / r - 1) * radial;
            }
        }
      const GrainLocator<dim> points(evaluated);

      const auto   &dof_handler = fluid.get_dof_handler();
      const auto   &fe          = dof_handler.get_fe();
      const auto   &solution    = fluid.get_solution();
      const auto   &mapping     = StaticMappingQ1<dim>::mapping;
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);
      // Per grain: the force and how many ranks evaluated it.
      std::vector<double>       local((dim + 1) * grains.size(), 0.);
      std::vector<bool>         done(grains.size(), false);
      std::vector<unsigned int> near, inside;
      std::vector<Point<dim>>   unit_points;
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          const BoundingBox<dim> box = cell->bounding_box();
          near.clear();
          points.grains_near_box(box, near);
          inside.clear();
          unit_points.clear();
          for (const unsigned int g : near)
            if (!done[g] && share[g] > 0 &&
                box.point_inside(evaluated[g].center, 1e-10))
              {
                // A centre on a face belongs to both cells (and maybe to
                // two ranks): counted once here, averaged over ranks below.
                Point<dim> unit;
                try
                  {
                    unit = mapping.transform_real_to_unit_cell(
                      cell, evaluated[g].center);
                  }
                catch (const typename Mapping<dim>::ExcTransformationFailed &)
                  {
                    continue;
                  }
                if (!GeometryInfo<dim>::is_inside_unit_cell(unit, 1e-10))
                  continue;
                done[g] = true;
                inside.push_back(g);
                unit_points.push_back(
                  GeometryInfo<dim>::project_to_unit_cell(unit));
              }
          if (inside.empty())
            continue;
          const fluid::PorousCell<dim> porous = zone->coefficients(*cell);
          const Quadrature<dim>        at_points(unit_points);
          FEValues<dim>                values(mapping,
                               fe,
                               at_points,
                               update_values | update_gradients);
          values.reinit(cell);
          std::vector<Tensor<1, dim>> u(inside.size()), grad_p(inside.size());
          values[velocities].get_function_values(solution, u);
          values[pressure].get_function_gradients(solution, grad_p);
          const double phi = porous.porosity;
          for (unsigned int k = 0; k < inside.size(); ++k)
            {
              const auto          &grain = grains[inside[k]];
              const Tensor<1, dim> relative = u[k] - phi * grain.velocity;
              const double         c = porous.drag(viscosity, density, relative);
              const Tensor<1, dim> force =
                share[inside[k]] * grain.measure() *
                (-grad_p[k] +
                 (phi < 1 ? phi * c / (1 - phi) : 0.) * relative);
              for (unsigned int d = 0; d < dim; ++d)
                local[(dim + 1) * inside[k] + d] += force[d];
              local[(dim + 1) * inside[k] + dim] += 1;
            }
        }
      std::vector<double> global(local.size());
      Utilities::MPI::sum(local, comm, global);
      for (unsigned int g = 0; g < grains.size(); ++g)
        if (const double count = global[(dim + 1) * g + dim]; count > 0)
          for (unsigned int d = 0; d < dim; ++d)
            forces.force[g][d] += global[(dim + 1) * g + d] / count;
    }


    template struct GrainForces<2>;
    template struct GrainForces<3>;
    template GrainForces<2>
    compute_grain_forces(const fluid::PenalizedNavierStokes<2> &,
                         const std::vector<dem::Grain<2>> &,
                         const ForceModel,
                         const MPI_Comm);
    template GrainForces<3>
    compute_grain_forces(const fluid::PenalizedNavierStokes<3> &,
                         const std::vector<dem::Grain<3>> &,
                         const ForceModel,
                         const MPI_Comm);
    template void
    add_porous_grain_forces(const fluid::PenalizedNavierStokes<2> &,
                            const std::vector<dem::Grain<2>> &,
                            const GrainSolidField<2> &,
                            const double,
                            const double,
                            GrainForces<2> &,
                            const MPI_Comm);
    template void
    add_porous_grain_forces(const fluid::PenalizedNavierStokes<3> &,
                            const std::vector<dem::Grain<3>> &,
                            const GrainSolidField<3> &,
                            const double,
                            const double,
                            GrainForces<3> &,
                            const MPI_Comm);
  } // namespace coupling
} // namespace softsand
