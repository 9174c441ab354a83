#ifndef softsand_dem_grain_h
#define softsand_dem_grain_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace softsand
{
  namespace dem
  {
    using namespace dealii;

    /**
     * A rigid spherical grain (a disk in 2D): the state that the fluid needs
     * to see (position, size, rigid velocity). The angular velocity always has
     * three components; in 2D only the z component is used.
     */
    template <int dim>
    struct Grain
    {
      Point<dim>     center;
      double         radius = 0;
      Tensor<1, dim> velocity;
      Tensor<1, 3>   angular_velocity;

      double
      diameter() const
      {
        return 2. * radius;
      }

      /// Rigid-body velocity v + w x (x - c) of the grain material at @p x.
      Tensor<1, dim>
      rigid_velocity(const Point<dim> &x) const;

      /// Volume of the sphere (3D) or area of the disk (2D).
      double
      measure() const;
    };


    /// The grains' mean diameter (0 without grains): the length of the
    /// pore Reynolds number.
    template <int dim>
    inline double
    mean_diameter(const std::vector<Grain<dim>> &grains)
    {
      double sum = 0;
      for (const auto &grain : grains)
        sum += grain.diameter();
      return grains.empty() ? 0. : sum / grains.size();
    }


    template <int dim>
    inline Tensor<1, dim>
    Grain<dim>::rigid_velocity(const Point<dim> &x) const
    {
      Tensor<1, dim> u = velocity;
      const Tensor<1, dim> r = x - center;
      if constexpr (dim == 2)
        {
          u[0] -= angular_velocity[2] * r[1];
          u[1] += angular_velocity[2] * r[0];
        }
      else
        {
          u[0] += angular_velocity[1] * r[2] - angular_velocity[2] * r[1];
          u[1] += angular_velocity[2] * r[0] - angular_velocity[0] * r[2];
          u[2] += angular_velocity[0] * r[1] - angular_velocity[1] * r[0];
        }
      return u;
    }


    template <int dim>
    inline double
    Grain<dim>::measure() const
    {
      if constexpr (dim == 2)
        return M_PI * radius * radius;
      else
        return 4. / 3. * M_PI * radius * radius * radius;
    }
  } // namespace dem
} // namespace softsand

#endif
