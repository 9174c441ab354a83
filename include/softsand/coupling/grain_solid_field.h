#ifndef softsand_coupling_grain_solid_field_h
#define softsand_coupling_grain_solid_field_h

#include <deal.II/base/parameter_handler.h>

#include <softsand/coupling/grain_locator.h>
#include <softsand/coupling/porous_zone.h>
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

      /// The hybrid model: grains resolved near the inlet's axis, a porous
      /// medium beyond (PorousZone). Cells of the porous zone then see no
      /// solid through evaluate(); the mesh is refined around the resolved
      /// grains only (refinement_locator()).
      void
      set_porous_zone(const HybridModelParameters &parameters,
                      const Point<dim>            &axis_point,
                      const Tensor<1, dim>        &axis,
                      const BoundingBox<dim>      &domain);

      const PorousZone<dim> *
      porous_zone() const
      {
        return zone.get();
      }

      fluid::PorousCell<dim>
      porous_cell(const CellAccessor<dim, dim> &cell) const override
      {
        return zone ? zone->porous_cell(cell) : fluid::PorousCell<dim>();
      }

      bool
      has_porous_zone() const override
      {
        return zone != nullptr;
      }

      /// The grains the mesh is refined around: all, or with a porous zone
      /// those that reach into the resolved one.
      const GrainLocator<dim> &
      refinement_locator() const
      {
        return resolved_locator ? *resolved_locator : grain_locator;
      }

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
      std::unique_ptr<PorousZone<dim>>    zone;
      std::vector<dem::Grain<dim>>        resolved_grains;
      std::unique_ptr<GrainLocator<dim>>  resolved_locator;

      bool
      in_porous_zone(const CellAccessor<dim, dim> &cell) const
      {
        return zone && zone->is_porous(cell);
      }
    };
  } // namespace coupling
} // namespace softsand

#endif
