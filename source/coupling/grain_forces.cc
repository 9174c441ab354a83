#include <softsand/coupling/grain_forces.h>

#include <deal.II/base/mpi.h>

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
  } // namespace coupling
} // namespace softsand
