#ifndef softsand_postprocess_columns_flow_regime_columns_h
#define softsand_postprocess_columns_flow_regime_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

#include <string>

namespace softsand
{
  namespace postprocess
  {
    /**
     * The flow regime of a scene with grains: the pore Reynolds number
     * rho |u| d / mu over the fluid cells, d the grains' mean diameter
     * (largest value and 95th percentile by volume). A model without
     * inertia (steady Stokes, the quasi-steady coupling) is valid for
     * Re_p << 1; above 1 the scene is warned once, naming the entry that
     * chose the model.
     */
    template <int dim>
    class FlowRegimeColumns : public FluidColumnSource<dim>
    {
    public:
      /// @p creeping_model: the entry and value that chose a model without
      /// inertia ("coupling/fluid model = quasi-steady"); empty when the
      /// model has inertia. @p inertial_model: the setting the warning
      /// proposes instead.
      FlowRegimeColumns(const double       density,
                        const double       viscosity,
                        const std::string &creeping_model,
                        const std::string &inertial_model);

      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;

    private:
      const double      density, viscosity;
      const std::string creeping_model, inertial_model;
    };
  } // namespace postprocess
} // namespace softsand

#endif
