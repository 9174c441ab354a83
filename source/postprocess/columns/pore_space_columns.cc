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

      // Freed contact cells are a cell thick: on coarse meshes they hand
      // much of a dense pack to the fluid (the small Hele-Shaw pack at 2
      // cells per mean diameter: 70x the flow rate).
      const double freed = s.fluid.freed_solid_fraction();
      row["freed_solid_fraction"] = freed;
      if (freed > 0.1)
        {
          std::ostringstream message;
          message.precision(3);
          message << when.str() << " the freed contact cells (fluid/free "
                  << "contact cells: cells within one cell of two grains or "
                  << "of a wall with an imposed velocity) hold " << 100 * freed
                  << " % of the grains' volume, which the fluid then flows "
                  << "through: the pack is far more permeable than its "
                  << "grains (column freed_solid_fraction). Raise mesh/cells "
                  << "per diameter, or set fluid/free contact cells = false.";
          base::warn_once("freed solid", message.str(), comm);
        }
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
