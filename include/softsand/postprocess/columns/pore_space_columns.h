#ifndef softsand_postprocess_columns_pore_space_columns_h
#define softsand_postprocess_columns_pore_space_columns_h

#include <softsand/postprocess/columns/fluid_column_source.h>

namespace softsand
{
  namespace postprocess
  {
    /**
     * The open pore space of a scene with grains (PoreConnectivity): its
     * volume, the fraction of it sealed in pockets that no open path joins
     * to an inlet or outlet, and whether an open path joins the inlet to
     * the outlet. Warns once when sealed pockets hold more than 1 % of the
     * open volume and when the inlet-outlet path closes.
     */
    template <int dim>
    class PoreSpaceColumns : public FluidColumnSource<dim>
    {
    public:
      void
      add_columns(const FluidSnapshot<dim> &snapshot,
                  Columns                  &row) const override;
    };
  } // namespace postprocess
} // namespace softsand

#endif
