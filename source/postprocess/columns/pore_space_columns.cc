#include <softsand/base/warnings.h>
#include <softsand/postprocess/columns/pore_space_columns.h>

#include <sstream>

namespace softsand
{
  namespace postprocess
  {
    template <int dim>
    void
    PoreSpaceColumns<dim>::add_columns(const FluidSnapshot<dim> &s,
                                       Columns                  &row) const
    {
      if (s.pores == nullptr)
        return;
      const auto  &pores  = *s.pores;
      const double sealed = pores.open_volume > 0 ?
                              pores.sealed_volume / pores.open_volume :
                              0.;
      row["open_pore_volume"]     = pores.open_volume;
      row["sealed_pore_fraction"] = sealed;
      if (pores.has_ends)
        row["open_path"] = pores.open_path ? 1 : 0;

      const MPI_Comm     comm = s.triangulation.get_communicator();
      std::ostringstream when;
      when.precision(3);
      when << "At step " << s.step << " (t = " << s.time << " s)";
      const std::string remedy =
        "The open cells are the uncovered ones (fluid/solid model = "
        "penalization with coupling/void fraction model = cell average: any "
        "covered part closes a cell at Theta >= 1e3) or those less than "
        "half covered (the other rules). Raise mesh/cells per diameter, or "
        "use fluid/solid model = rigid nodes or coupling/void fraction "
        "model = cell majority.";
      if (sealed > 0.01)
        {
          std::ostringstream message;
          message.precision(3);
          message << when.str() << " " << 100 * sealed
                  << " % of the open pore volume lies in pockets that no "
                  << "open path joins to an inlet or an outlet: no flow "
                  << "enters them and their pressure is not set by the flow "
                  << "(it floats). Mean pressures (ring_pressure_*) are taken "
                  << "over the connected pore space only; the field output's "
                  << "pore_space marks the pockets with 2. " << remedy;
          base::warn_once("sealed pockets", message.str(), comm);
        }
      if (!pores.open_path)
        {
          std::ostringstream message;
          message << when.str() << " no open path joins the inlet to the "
                  << "outlet: the pore space is sealed at this resolution, "
                  << "the flow crosses only covered (penalized) cells and "
                  << "the permeability columns measure the penalty, not the "
                  << "pack. " << remedy;
          base::warn_once("sealed path", message.str(), comm);
        }
    }

    template class PoreSpaceColumns<2>;
    template class PoreSpaceColumns<3>;
  } // namespace postprocess
} // namespace softsand
