// Local tensors of a Q2-Q1 cell on the kernels' lexicographic numbering:
// the velocity mass and Laplacian diagonals, the pressure-velocity coupling
// and the Q1 Laplacian, from 1D reference integrals on axis-parallel boxes
// (FEValues on any other cell). The transient matrix-free step assembles
// B, B^T, the diagonal D and the rigid-node smoothing from them.
#ifndef softsand_fluid_box_cell_tensors_h
#define softsand_fluid_box_cell_tensors_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <vector>

namespace softsand
{
  namespace fluid
  {
    namespace internal
    {
      using namespace dealii;

      /// Integrals of the 1D Q2 Lagrange basis (nodes 0, 1/2, 1) and the Q1
      /// basis on (0, 1): the tensor factors of the local matrices on a box.
      struct ReferenceIntegrals
      {
        double mass2[3], stiff2[3]; // int phi_i^2, int phi_i'^2
        double mixed[2][3];         // int psi_a phi_i
        double mixed_grad[2][3];    // int psi_a phi_i'
        double mass1[2][2], stiff1[2][2];

        ReferenceIntegrals()
        {
          const QGauss<1> gauss(3);
          const auto phi = [](const unsigned int i, const double x) {
            return i == 0 ? 2 * (x - 0.5) * (x - 1) :
                            (i == 1 ? -4 * x * (x - 1) : 2 * x * (x - 0.5));
          };
          const auto dphi = [](const unsigned int i, const double x) {
            return i == 0 ? 4 * x - 3 : (i == 1 ? 4 - 8 * x : 4 * x - 1);
          };
          const auto psi = [](const unsigned int a, const double x) {
            return a == 0 ? 1 - x : x;
          };
          const auto dpsi = [](const unsigned int a, const double) {
            return a == 0 ? -1. : 1.;
          };
          for (unsigned int i = 0; i < 3; ++i)
            {
              mass2[i] = stiff2[i] = 0;
              for (unsigned int a = 0; a < 2; ++a)
                mixed[a][i] = mixed_grad[a][i] = 0;
            }
          for (unsigned int a = 0; a < 2; ++a)
            for (unsigned int b = 0; b < 2; ++b)
              mass1[a][b] = stiff1[a][b] = 0;
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const double x = gauss.point(q)[0], w = gauss.weight(q);
              for (unsigned int i = 0; i < 3; ++i)
                {
                  mass2[i] += phi(i, x) * phi(i, x) * w;
                  stiff2[i] += dphi(i, x) * dphi(i, x) * w;
                  for (unsigned int a = 0; a < 2; ++a)
                    {
                      mixed[a][i] += psi(a, x) * phi(i, x) * w;
                      mixed_grad[a][i] += psi(a, x) * dphi(i, x) * w;
                    }
                }
              for (unsigned int a = 0; a < 2; ++a)
                for (unsigned int b = 0; b < 2; ++b)
                  {
                    mass1[a][b] += psi(a, x) * psi(b, x) * w;
                    stiff1[a][b] += dpsi(a, x) * dpsi(b, x) * w;
                  }
            }
        }
      };

      /// The edges of an axis-parallel box cell, or zeros for another.
      template <int dim>
      Tensor<1, dim>
      box_edges(const CellAccessor<dim, dim> &cell)
      {
        const Point<dim> origin = cell.vertex(0);
        Tensor<1, dim>   edges  = cell.vertex((1 << dim) - 1) - origin;
        for (unsigned int d = 0; d < dim; ++d)
          if (!(edges[d] > 0))
            return Tensor<1, dim>();
        for (unsigned int v = 0; v < (1u << dim); ++v)
          {
            Point<dim> expected = origin;
            for (unsigned int d = 0; d < dim; ++d)
              if (v & (1u << d))
                expected[d] += edges[d];
            if (expected.distance(cell.vertex(v)) > 1e-10 * edges.norm())
              return Tensor<1, dim>();
          }
        return edges;
      }

      /// Local tensors of one cell in the lexicographic numbering of the
      /// matrix-free kernels: per scalar Q2 function l the diagonal of the
      /// mass and of the Laplacian, per direction c the pressure-velocity
      /// coupling int psi_a d_c phi_l, and the Q1 Laplacian.
      template <int dim>
      struct LocalTensors
      {
        static constexpr unsigned int n_u = Utilities::pow(3, dim);
        static constexpr unsigned int n_p = Utilities::pow(2, dim);
        std::array<double, n_u>                      mass, stiffness;
        std::array<std::array<double, n_u>, dim * n_p> coupling; // [c*n_p+a][l]
        FullMatrix<double>                           pressure_laplace{n_p, n_p};
      };

      template <int dim>
      class LocalTensorComputer
      {
      public:
        LocalTensorComputer()
          : scalar_q2(2)
          , scalar_q1(1)
          , quadrature(3)
          , q2_values(scalar_q2,
                      quadrature,
                      update_values | update_gradients | update_JxW_values)
          , q1_values(scalar_q1, quadrature, update_values | update_gradients)
          , h2l(FETools::hierarchic_to_lexicographic_numbering<dim>(2))
        {}

        void
        compute(const typename Triangulation<dim>::active_cell_iterator &cell,
                LocalTensors<dim>                                        &t)
        {
          constexpr unsigned int n_u = LocalTensors<dim>::n_u,
                                 n_p = LocalTensors<dim>::n_p;
          const Tensor<1, dim>   h   = box_edges<dim>(*cell);
          if (h.norm() > 0)
            {
              double volume = 1;
              for (unsigned int d = 0; d < dim; ++d)
                volume *= h[d];
              for (unsigned int l = 0; l < n_u; ++l)
                {
                  unsigned int idx[dim];
                  for (unsigned int d = 0, r = l; d < dim; ++d, r /= 3)
                    idx[d] = r % 3;
                  double m = volume, s = 0;
                  for (unsigned int d = 0; d < dim; ++d)
                    m *= ref.mass2[idx[d]];
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      double term = volume / (h[c] * h[c]) * ref.stiff2[idx[c]];
                      for (unsigned int d = 0; d < dim; ++d)
                        if (d != c)
                          term *= ref.mass2[idx[d]];
                      s += term;
                    }
                  t.mass[l]      = m;
                  t.stiffness[l] = s;
                  for (unsigned int a = 0; a < n_p; ++a)
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        double term = volume / h[c];
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            const unsigned int ad = (a >> d) & 1u;
                            term *= (d == c) ? ref.mixed_grad[ad][idx[d]] :
                                               ref.mixed[ad][idx[d]];
                          }
                        t.coupling[c * n_p + a][l] = term;
                      }
                }
              for (unsigned int a = 0; a < n_p; ++a)
                for (unsigned int b = 0; b < n_p; ++b)
                  {
                    double sum = 0;
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        double term = volume / (h[c] * h[c]);
                        for (unsigned int d = 0; d < dim; ++d)
                          {
                            const unsigned int ad = (a >> d) & 1u,
                                               bd = (b >> d) & 1u;
                            term *= (d == c) ? ref.stiff1[ad][bd] :
                                               ref.mass1[ad][bd];
                          }
                        sum += term;
                      }
                    t.pressure_laplace(a, b) = sum;
                  }
              return;
            }
          // Any other cell: the same integrals with FEValues (Q1 numbers its
          // vertices lexicographically).
          q2_values.reinit(cell);
          q1_values.reinit(cell);
          for (unsigned int l = 0; l < n_u; ++l)
            {
              t.mass[l] = t.stiffness[l] = 0;
              for (unsigned int k = 0; k < dim * n_p; ++k)
                t.coupling[k][l] = 0;
            }
          t.pressure_laplace = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double JxW = q2_values.JxW(q);
              for (unsigned int b = 0; b < n_u; ++b)
                {
                  const unsigned int l   = h2l[b];
                  const double       phi = q2_values.shape_value(b, q);
                  const auto        &g   = q2_values.shape_grad(b, q);
                  t.mass[l] += phi * phi * JxW;
                  t.stiffness[l] += g * g * JxW;
                  for (unsigned int a = 0; a < n_p; ++a)
                    for (unsigned int c = 0; c < dim; ++c)
                      t.coupling[c * n_p + a][l] +=
                        q1_values.shape_value(a, q) * g[c] * JxW;
                }
              for (unsigned int a = 0; a < n_p; ++a)
                for (unsigned int b = 0; b < n_p; ++b)
                  t.pressure_laplace(a, b) += q1_values.shape_grad(a, q) *
                                              q1_values.shape_grad(b, q) * JxW;
            }
        }

      private:
        const ReferenceIntegrals  ref;
        FE_Q<dim>                 scalar_q2, scalar_q1;
        QGauss<dim>               quadrature;
        FEValues<dim>             q2_values, q1_values;
        std::vector<unsigned int> h2l;
      };
    } // namespace internal
  }   // namespace fluid
} // namespace softsand

#endif
