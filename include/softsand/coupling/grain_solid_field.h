#ifndef softsand_coupling_grain_solid_field_h
#define softsand_coupling_grain_solid_field_h

#include <deal.II/base/parameter_handler.h>

#include <softsand/coupling/grain_locator.h>
#include <softsand/fluid/solid_field.h>

#include <memory>

namespace softsand
{
  namespace coupling
  {
    /**
     * How grains are seen by the fluid mesh (doc/architecture.md).
     * quadrature point: the exact solid indicator at each quadrature point;
     * cell average: the paper's cell void fraction, the covered fraction of
     * the cell (sub-sampled), constant over the cell;
     * cell majority: the same staircase, but a cut cell is solid (vf = 0)
     * only where grains cover at least half of it and fluid otherwise. With
     * a large Theta the cell average makes every cut cell solid, and on Q2
     * elements the nodes on the faces of those cells are held too: the
     * no-slip surface sits on average half a cell outside the grain. The
     * majority rule puts it on the grain on average.
     */
    struct VoidFractionParameters
    {
      enum class Model
      {
        quadrature_point,
        cell_average,
        cell_majority
      };
      Model        model        = Model::cell_average;
      unsigned int subdivisions = 4;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };


    /**
     * Void fraction and grain rigid velocity on the fluid mesh, computed from
     * the exact sphere geometry of the grains.
     */
    template <int dim>
    class GrainSolidField : public fluid::SolidField<dim>
    {
    public:
      GrainSolidField(const std::vector<dem::Grain<dim>> &grains,
                      const VoidFractionParameters       &parameters);

      void
      evaluate(const CellAccessor<dim, dim> &cell,
               const std::vector<Point<dim>>  &points,
               std::vector<double>            &void_fraction,
               std::vector<Tensor<1, dim>>    &solid_velocity,
               std::vector<int>               &solid_index) const override;

      void
      evaluate_exact(const CellAccessor<dim, dim> &cell,
                     const std::vector<Point<dim>>  &points,
                     std::vector<double>            &void_fraction,
                     std::vector<Tensor<1, dim>>    &solid_velocity,
                     std::vector<int>               &solid_index,
                     const double inflation = 0) const override;

      unsigned int
      n_solids_near(const CellAccessor<dim, dim> &cell,
                    const double                  reach) const override;

      /// Covered fraction of the cell, sub-sampled: 1 - vf_cell. Also returns
      /// the grain covering most of the cell (-1 if none).
      double
      cell_solid_fraction(
        const CellAccessor<dim, dim> &cell,
        int &dominant_grain) const;

      const GrainLocator<dim> &
      locator() const
      {
        return grain_locator;
      }

    private:
      const std::vector<dem::Grain<dim>> &grains;
      VoidFractionParameters              parameters;
      GrainLocator<dim>                   grain_locator;
    };
  } // namespace coupling
} // namespace softsand

#endif
