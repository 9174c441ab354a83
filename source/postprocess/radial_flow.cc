#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>

#include <deal.II/fe/fe_values.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/radial_flow.h>

#include <array>
#include <cmath>

namespace softsand
{
  namespace postprocess
  {
    void
    RadialFlowParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      prm.enter_subsection("radial flow");
      prm.declare_entry(
        "radii",
        "",
        Patterns::List(Patterns::Double(0)),
        "Radii of pressure rings around the axis of boundary conditions/"
        "inlet region (m, ascending, at least two); empty: off. Statistics "
        "columns ring_pressure_K (fluid mean, Pa), radial_flow_rate "
        "(outward, m^3/s, between the first and last ring) and "
        "radial_permeability_K (Darcy permeability of the annulus between "
        "rings K and K+1, m^2) and radial_permeability (first to last "
        "ring), for a layer as thick as the mesh box along the axis.");
      prm.declare_entry("ring half width",
                        "0",
                        Patterns::Double(0),
                        "Half width of a pressure ring (m); 0: half the "
                        "finest cell.");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    void
    RadialFlowParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("postprocessing");
      prm.enter_subsection("radial flow");
      radii.clear();
      for (const auto &s :
           Utilities::split_string_list(prm.get("radii"), ','))
        radii.push_back(Utilities::string_to_double(s));
      if (radii.size() == 1)
        base::throw_invalid_parameter("postprocessing/radial flow/radii",
                                      prm.get("radii"),
                                      "give at least two radii, or none");
      for (unsigned int k = 1; k < radii.size(); ++k)
        if (!(radii[k] > radii[k - 1]))
          base::throw_invalid_parameter("postprocessing/radial flow/radii",
                                        prm.get("radii"),
                                        "radii must be > 0 and ascending");
      if (!radii.empty() && !(radii[0] > 0))
        base::throw_invalid_parameter("postprocessing/radial flow/radii",
                                      prm.get("radii"),
                                      "radii must be > 0 and ascending");
      ring_half_width = prm.get_double("ring half width");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    double
    RadialFlow::permeability(const std::vector<double> &radii,
                             const unsigned int         k,
                             const unsigned int         l,
                             const double               Q,
                             const double               mu,
                             const double               thickness) const
    {
      const double dp = ring_pressure[k] - ring_pressure[l];
      if (dp == 0)
        return 0;
      return Q * mu * std::log(radii[l] / radii[k]) /
             (2 * M_PI * thickness * dp);
    }


    template <int dim>
    RadialFlow
    compute_radial_flow(const DoFHandler<dim>                    &dof_handler,
                        const TrilinosWrappers::MPI::BlockVector &solution,
                        const fluid::SolidField<dim>             *solids,
                        const fluid::PressureRegion<dim>         &region,
                        const std::vector<double>                &radii,
                        const double                              half_width,
                        const PoreConnectivity                   *pores)
    {
      RadialFlow         result;
      const unsigned int n = radii.size();
      if (n < 2)
        return result;
      const auto       &fe = dof_handler.get_fe();
      const QGauss<dim> quadrature(fe.degree + 2);
      // The system's values (pressure) only where a ring crosses a cell;
      // the velocity everywhere from its scalar element's values at the
      // points, tabulated once (the system's FEValues copied all 89 shape
      // functions' values per cell: most of this pass).
      FEValues<dim> fe_values(fe, quadrature, update_values);
      const FiniteElement<dim> &fe_scalar = fe.base_element(0);
      FEValues<dim>             geometry(fe_scalar,
                             quadrature,
                             update_quadrature_points | update_JxW_values);
      const FEValuesExtractors::Scalar pressure(dim);
      const unsigned int               n_q = quadrature.size();
      const unsigned int n_nodes = fe_scalar.n_dofs_per_cell();
      Table<2, double>   shape(n_nodes, n_q);
      for (unsigned int b = 0; b < n_nodes; ++b)
        for (unsigned int q = 0; q < n_q; ++q)
          shape(b, q) = fe_scalar.shape_value(b, quadrature.point(q));
      std::vector<std::array<unsigned int, dim>> node_dofs(n_nodes);
      for (unsigned int b = 0; b < n_nodes; ++b)
        for (unsigned int c = 0; c < dim; ++c)
          node_dofs[b][c] = fe.component_to_system_index(c, b);
      Vector<double>                   cell_values(fe.n_dofs_per_cell());
      std::vector<double>              p(n_q), vf(n_q, 1.);
      std::vector<Tensor<1, dim>>      u(n_q), u_s(n_q);
      std::vector<int>                 index(n_q);
      // Per ring: fluid-weighted pressure and weight; per annulus: flux;
      // per ring: pressure and weight over the connected pore space.
      std::vector<double> sums(5 * n, 0.);
      const double        reach = radii.back() + half_width;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            // Skip cells entirely inside the first ring or beyond the last.
            const double rc = region.distance_from_axis(cell->center());
            const double half_diagonal = 0.5 * cell->diameter();
            if (rc + half_diagonal < radii[0] - half_width ||
                rc - half_diagonal > reach)
              continue;
            const bool connected =
              pores == nullptr || pores->connected(cell->active_cell_index());
            // Between the rings only the flux is summed: the pressure and
            // the solid fraction (the grains' lookup, most of this pass)
            // are needed only in cells a ring crosses.
            bool on_ring = false;
            for (const double radius : radii)
              on_ring = on_ring || std::abs(rc - radius) <=
                                     half_width + half_diagonal;
            geometry.reinit(cell);
            cell->get_dof_values(solution, cell_values);
            for (unsigned int q = 0; q < n_q; ++q)
              {
                u[q] = Tensor<1, dim>();
                for (unsigned int b = 0; b < n_nodes; ++b)
                  for (unsigned int c = 0; c < dim; ++c)
                    u[q][c] += cell_values(node_dofs[b][c]) * shape(b, q);
              }
            if (on_ring)
              {
                fe_values.reinit(cell);
                fe_values[pressure].get_function_values(solution, p);
                if (solids != nullptr)
                  solids->evaluate(
                    *cell, geometry.get_quadrature_points(), vf, u_s, index);
              }
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const Point<dim> &x = geometry.quadrature_point(q);
                Tensor<1, dim>    e = x - region.center;
                if (dim == 3)
                  e -= (e * region.axis) * region.axis;
                const double r = e.norm();
                if (!(r > 0))
                  continue;
                e /= r;
                const double JxW = geometry.JxW(q);
                for (unsigned int k = 0; k < n; ++k)
                  {
                    if (std::abs(r - radii[k]) <= half_width)
                      {
                        sums[k] += vf[q] * p[q] * JxW;
                        sums[n + k] += vf[q] * JxW;
                        if (connected)
                          {
                            sums[3 * n + k] += vf[q] * p[q] * JxW;
                            sums[4 * n + k] += vf[q] * JxW;
                          }
                      }
                    if (k + 1 < n && r >= radii[k] && r < radii[k + 1])
                      sums[2 * n + k] += (u[q] * e) * JxW;
                  }
              }
          }
      Utilities::MPI::sum(sums, dof_handler.get_communicator(), sums);
      double total = 0;
      for (unsigned int k = 0; k < n; ++k)
        {
          AssertThrow(sums[n + k] > 0,
                      ExcMessage("Parameter <postprocessing/radial flow/"
                                 "radii>: the ring at " +
                                 Utilities::to_string(radii[k]) +
                                 " m crosses no fluid; choose radii inside "
                                 "the domain."));
          result.ring_pressure.push_back(sums[4 * n + k] > 0 ?
                                           sums[3 * n + k] / sums[4 * n + k] :
                                           sums[k] / sums[n + k]);
          if (k + 1 < n)
            {
              result.flow_rate.push_back(sums[2 * n + k] /
                                         (radii[k + 1] - radii[k]));
              total += sums[2 * n + k];
            }
        }
      result.total_flow_rate = total / (radii.back() - radii.front());
      return result;
    }

    template RadialFlow
    compute_radial_flow(const DoFHandler<2> &,
                        const TrilinosWrappers::MPI::BlockVector &,
                        const fluid::SolidField<2> *,
                        const fluid::PressureRegion<2> &,
                        const std::vector<double> &,
                        const double,
                        const PoreConnectivity *);
    template RadialFlow
    compute_radial_flow(const DoFHandler<3> &,
                        const TrilinosWrappers::MPI::BlockVector &,
                        const fluid::SolidField<3> *,
                        const fluid::PressureRegion<3> &,
                        const std::vector<double> &,
                        const double,
                        const PoreConnectivity *);
  } // namespace postprocess
} // namespace softsand
