#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/flow_diagnostics.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace softsand
{
  namespace postprocess
  {
    namespace
    {
      /// The paper's fluid cells: cell void fraction above this.
      constexpr double fluid_cell_void_fraction = 0.9;
    } // namespace


    void
    PostprocessingParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      prm.declare_entry("flow axis",
                        "x",
                        Patterns::Selection("x|y|z"),
                        "Mean flow direction: pressure drop, permeability "
                        "and drag are measured along it.");
      prm.declare_entry(
        "pressure drop planes",
        "",
        Patterns::List(Patterns::Double(), 0, 2),
        "Two positions along the flow axis (m) between which the pressure "
        "drop is measured as the difference of fluid-averaged pressures in "
        "thin slabs; empty: between the two boundary faces normal to the "
        "flow axis.");
      prm.declare_entry("reference velocity",
                        "0",
                        Patterns::Double(0),
                        "Velocity U of the drag coefficient and the Stokes "
                        "drag 3 pi mu d U (m/s); 0: the imposed inflow "
                        "velocity.");
      prm.declare_entry("exact velocity",
                        "",
                        Patterns::Anything(),
                        "Optional exact velocity (expressions in x, y, z, "
                        "t separated by ';'): L2/H1 errors are reported.");
      prm.declare_entry("exact pressure",
                        "",
                        Patterns::Anything(),
                        "Optional exact pressure (expression in x, y, z, "
                        "t), compared up to a constant.");
      prm.declare_entry("write grain forces",
                        "true",
                        Patterns::Bool(),
                        "Write grain_forces.txt (force and torque per "
                        "grain) at each output.");
      prm.declare_entry("eq7 forces",
                        "false",
                        Patterns::Bool(),
                        "Compute the paper's Eq. 7 fluid force on each grain "
                        "(the stress divergence over the grain's cells) "
                        "beside the reaction force, as a diagnostic: the "
                        "eq7_* statistics columns and grain_forces.txt "
                        "columns. It costs one more pass over the cells "
                        "every step, so it is off unless asked for; always "
                        "on with coupling/force model = paper eq7.");
      prm.leave_subsection();
    }


    void
    PostprocessingParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      const std::string axis = prm.get("flow axis");
      flow_axis              = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
      pressure_planes.clear();
      for (const auto &s :
           Utilities::split_string_list(prm.get("pressure drop planes"), ','))
        pressure_planes.push_back(Utilities::string_to_double(s));
      if (pressure_planes.size() == 1)
        base::throw_invalid_parameter("postprocessing/pressure drop planes",
                                      prm.get("pressure drop planes"),
                                      "give two positions or none");
      reference_velocity = prm.get_double("reference velocity");
      exact_velocity     = prm.get("exact velocity");
      exact_pressure     = prm.get("exact pressure");
      write_grain_forces = prm.get_bool("write grain forces");
      eq7_forces         = prm.get_bool("eq7 forces");
      prm.leave_subsection();
    }


    template <int dim>
    double
    boundary_flux(const DoFHandler<dim> &dof_handler,
                  const BlockVector     &solution,
                  const unsigned int     boundary_id)
    {
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim - 1> quadrature(fe.degree + 1);
      FEFaceValues<dim> fe_face_values(fe,
                                       quadrature,
                                       update_values | update_normal_vectors |
                                         update_JxW_values);
      const FEValuesExtractors::Vector velocities(0);
      std::vector<Tensor<1, dim>>      u(quadrature.size());
      double                           flux = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary_id)
              {
                fe_face_values.reinit(cell, face);
                fe_face_values[velocities].get_function_values(solution, u);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  flux += u[q] * fe_face_values.normal_vector(q) *
                          fe_face_values.JxW(q);
              }
      return Utilities::MPI::sum(flux, dof_handler.get_communicator());
    }


    template <int dim>
    double
    boundary_area(const DoFHandler<dim> &dof_handler,
                  const unsigned int     boundary_id)
    {
      double area = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary_id)
              area += face->measure();
      return Utilities::MPI::sum(area, dof_handler.get_communicator());
    }


    template <int dim>
    double
    boundary_mean_pressure(const DoFHandler<dim> &dof_handler,
                           const BlockVector     &solution,
                           const unsigned int     boundary_id)
    {
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim - 1> quadrature(fe.degree + 1);
      FEFaceValues<dim> fe_face_values(fe,
                                       quadrature,
                                       update_values | update_JxW_values);
      const FEValuesExtractors::Scalar pressure(dim);
      std::vector<double>              p(quadrature.size());
      double                           sums[2] = {0, 0};
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary_id)
              {
                fe_face_values.reinit(cell, face);
                fe_face_values[pressure].get_function_values(solution, p);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  {
                    sums[0] += p[q] * fe_face_values.JxW(q);
                    sums[1] += fe_face_values.JxW(q);
                  }
              }
      Utilities::MPI::sum(ArrayView<const double>(sums, 2),
                          dof_handler.get_communicator(),
                          ArrayView<double>(sums, 2));
      return sums[1] > 0 ? sums[0] / sums[1] : 0.;
    }


    template <int dim>
    double
    slab_mean_pressure(const DoFHandler<dim>        &dof_handler,
                       const BlockVector            &solution,
                       const fluid::SolidField<dim> *solids,
                       const unsigned int            axis,
                       const double                  position,
                       const double                  half_width)
    {
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim> quadrature(fe.degree + 2);
      FEValues<dim>     fe_values(fe,
                              quadrature,
                              update_values | update_quadrature_points |
                                update_JxW_values);
      const FEValuesExtractors::Scalar pressure(dim);
      const unsigned int               n_q = quadrature.size();
      std::vector<double>              p(n_q), vf(n_q, 1.);
      std::vector<Tensor<1, dim>>      u_s(n_q);
      std::vector<int>                 index(n_q);
      double                           sums[2] = {0, 0};
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto box = cell->bounding_box();
            if (box.get_boundary_points().second[axis] < position - half_width ||
                box.get_boundary_points().first[axis] > position + half_width)
              continue;
            fe_values.reinit(cell);
            fe_values[pressure].get_function_values(solution, p);
            if (solids != nullptr)
              solids->evaluate(
                *cell,
                fe_values.get_quadrature_points(),
                vf,
                u_s,
                index);
            for (unsigned int q = 0; q < n_q; ++q)
              if (std::abs(fe_values.quadrature_point(q)[axis] - position) <=
                  half_width)
                {
                  sums[0] += vf[q] * p[q] * fe_values.JxW(q);
                  sums[1] += vf[q] * fe_values.JxW(q);
                }
          }
      Utilities::MPI::sum(ArrayView<const double>(sums, 2),
                          dof_handler.get_communicator(),
                          ArrayView<double>(sums, 2));
      AssertThrow(sums[1] > 0,
                  ExcMessage("Parameter <postprocessing/pressure drop "
                             "planes>: the plane at " +
                             Utilities::to_string(position) +
                             " m crosses no fluid; choose positions inside "
                             "the domain."));
      return sums[0] / sums[1];
    }


    template <int dim>
    Tensor<1, dim>
    boundary_traction(const DoFHandler<dim> &dof_handler,
                      const BlockVector     &solution,
                      const double           viscosity)
    {
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim - 1> quadrature(fe.degree + 1);
      FEFaceValues<dim> fe_face_values(fe,
                                       quadrature,
                                       update_values | update_gradients |
                                         update_normal_vectors |
                                         update_JxW_values);
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);
      std::vector<Tensor<2, dim>>      grad_u(quadrature.size());
      std::vector<double>              p(quadrature.size());
      Tensor<1, dim>                   force;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                fe_face_values.reinit(cell, face);
                fe_face_values[velocities].get_function_gradients(solution,
                                                                  grad_u);
                fe_face_values[pressure].get_function_values(solution, p);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  {
                    const Tensor<1, dim> &n = fe_face_values.normal_vector(q);
                    force += (viscosity * (grad_u[q] * n) - p[q] * n) *
                             fe_face_values.JxW(q);
                  }
              }
      return Utilities::MPI::sum(force, dof_handler.get_communicator());
    }


    template <int dim>
    Porosity
    compute_porosity(const Triangulation<dim>             &tria,
                     const coupling::GrainSolidField<dim> &solids,
                     const unsigned int                    axis,
                     const double                          lower,
                     const double                          upper)
    {
      double sums[3] = {0, 0, 0}; // fluid cells' volume, vf integral, volume
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            double inside = 1; // part of the cell between the planes
            if (lower < upper)
              {
                const auto   box = cell->bounding_box();
                const double a   = box.lower_bound(axis);
                const double b   = box.upper_bound(axis);
                inside = std::max(0., std::min(b, upper) - std::max(a, lower)) / (b - a);
                if (inside == 0)
                  continue;
              }
            int          grain;
            const double vf = 1. - solids.cell_solid_fraction(*cell, grain);
            const double v  = inside * cell->measure();
            if (vf > fluid_cell_void_fraction)
              sums[0] += v;
            sums[1] += vf * v;
            sums[2] += v;
          }
      Utilities::MPI::sum(ArrayView<const double>(sums, 3),
                          tria.get_communicator(),
                          ArrayView<double>(sums, 3));
      return {sums[0] / sums[2], sums[1] / sums[2]};
    }


    template <int dim>
    PoreReynolds
    compute_pore_reynolds(const DoFHandler<dim>                &dof_handler,
                          const BlockVector                    &solution,
                          const coupling::GrainSolidField<dim> &solids,
                          const double                          density,
                          const double                          viscosity,
                          const double                          diameter)
    {
      // Volume of fluid per bin of log10(Re), 1e-15 to 1e10; the first bin
      // also takes Re = 0 and below, the last everything above.
      constexpr int    bins_per_decade = 50;
      constexpr double lowest_decade   = -15;
      constexpr int    n_bins          = 25 * bins_per_decade;
      std::vector<double> volume(n_bins, 0.);
      double              max_re = 0;

      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim> quadrature(2);
      FEValues<dim>     fe_values(fe, quadrature, update_values | update_JxW_values);
      const FEValuesExtractors::Vector velocities(0);
      std::vector<Tensor<1, dim>>      u(quadrature.size());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            int grain;
            if (1. - solids.cell_solid_fraction(*cell, grain) <=
                fluid_cell_void_fraction)
              continue;
            fe_values.reinit(cell);
            fe_values[velocities].get_function_values(solution, u);
            double speed = 0, v = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                speed += u[q].norm() * fe_values.JxW(q);
                v += fe_values.JxW(q);
              }
            const double re = density * (speed / v) * diameter / viscosity;
            max_re          = std::max(max_re, re);
            const double position =
              re > 0 ? (std::log10(re) - lowest_decade) * bins_per_decade : 0;
            volume[std::clamp(static_cast<int>(position), 0, n_bins - 1)] += v;
          }
      Utilities::MPI::sum(volume, dof_handler.get_communicator(), volume);
      PoreReynolds result;
      result.max = Utilities::MPI::max(max_re, dof_handler.get_communicator());
      const double total = std::accumulate(volume.begin(), volume.end(), 0.);
      double       below = 0;
      for (int b = 0; b < n_bins; ++b)
        {
          below += volume[b];
          if (below >= 0.95 * total)
            {
              // The bin's upper edge, never above the largest value.
              result.p95 = std::min(
                result.max,
                std::pow(10., lowest_decade + (b + 1.) / bins_per_decade));
              break;
            }
        }
      return result;
    }


    template <int dim>
    ErrorNorms
    compute_errors(const DoFHandler<dim> &dof_handler,
                   const BlockVector     &solution,
                   const Function<dim>   &exact)
    {
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim> quadrature(fe.degree + 2);
      FEValues<dim>     fe_values(fe,
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);
      const unsigned int               n_q = quadrature.size();
      std::vector<Tensor<1, dim>>      u(n_q);
      std::vector<Tensor<2, dim>>      grad_u(n_q);
      std::vector<double>              p(n_q);
      std::vector<Vector<double>>      exact_values(n_q, Vector<double>(dim + 1));
      std::vector<std::vector<Tensor<1, dim>>> exact_gradients(
        n_q, std::vector<Tensor<1, dim>>(dim + 1));

      // First pass: mean pressure difference; second: the norms.
      double sums[6] = {0, 0, 0, 0, 0, 0};
      for (unsigned int pass = 0; pass < 2; ++pass)
        {
          const double mean_difference = pass == 1 ? sums[0] / sums[1] : 0.;
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                fe_values.reinit(cell);
                fe_values[velocities].get_function_values(solution, u);
                fe_values[velocities].get_function_gradients(solution, grad_u);
                fe_values[pressure].get_function_values(solution, p);
                exact.vector_value_list(fe_values.get_quadrature_points(),
                                        exact_values);
                exact.vector_gradient_list(fe_values.get_quadrature_points(),
                                           exact_gradients);
                for (unsigned int q = 0; q < n_q; ++q)
                  {
                    const double JxW = fe_values.JxW(q);
                    const double dp  = p[q] - exact_values[q][dim];
                    if (pass == 0)
                      {
                        sums[0] += dp * JxW;
                        sums[1] += JxW;
                        continue;
                      }
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        const double du = u[q][d] - exact_values[q][d];
                        sums[2] += du * du * JxW;
                        sums[3] += (grad_u[q][d] - exact_gradients[q][d]) *
                                   (grad_u[q][d] - exact_gradients[q][d]) *
                                   JxW;
                      }
                    sums[4] += (dp - mean_difference) * (dp - mean_difference) *
                               JxW;
                  }
              }
          if (pass == 0)
            Utilities::MPI::sum(ArrayView<const double>(sums, 2),
                                dof_handler.get_communicator(),
                                ArrayView<double>(sums, 2));
        }
      Utilities::MPI::sum(ArrayView<const double>(sums + 2, 3),
                          dof_handler.get_communicator(),
                          ArrayView<double>(sums + 2, 3));
      return {std::sqrt(sums[2]), std::sqrt(sums[3]), std::sqrt(sums[4])};
    }

#define SOFTSAND_INSTANTIATE(dim)                                           \
  template double boundary_flux(const DoFHandler<dim> &,                    \
                                const BlockVector &,                        \
                                const unsigned int);                        \
  template double boundary_area(const DoFHandler<dim> &,                    \
                                const unsigned int);                        \
  template double boundary_mean_pressure(const DoFHandler<dim> &,           \
                                         const BlockVector &,               \
                                         const unsigned int);               \
  template double slab_mean_pressure(const DoFHandler<dim> &,               \
                                     const BlockVector &,                   \
                                     const fluid::SolidField<dim> *,        \
                                     const unsigned int,                    \
                                     const double,                          \
                                     const double);                         \
  template Tensor<1, dim> boundary_traction(const DoFHandler<dim> &,        \
                                            const BlockVector &,            \
                                            const double);                  \
  template Porosity compute_porosity(const Triangulation<dim> &,            \
                                     const coupling::GrainSolidField<dim> &, \
                                     const unsigned int,                    \
                                     const double,                          \
                                     const double);                         \
  template PoreReynolds compute_pore_reynolds(                              \
    const DoFHandler<dim> &,                                                 \
    const BlockVector &,                                                     \
    const coupling::GrainSolidField<dim> &,                                  \
    const double,                                                            \
    const double,                                                            \
    const double);                                                           \
  template ErrorNorms compute_errors(const DoFHandler<dim> &,               \
                                     const BlockVector &,                   \
                                     const Function<dim> &);
    SOFTSAND_INSTANTIATE(2)
    SOFTSAND_INSTANTIATE(3)
#undef SOFTSAND_INSTANTIATE
  } // namespace postprocess
} // namespace softsand
