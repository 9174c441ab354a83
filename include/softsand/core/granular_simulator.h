#ifndef softsand_core_granular_simulator_h
#define softsand_core_granular_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <softsand/core/parameters.h>
#include <softsand/dem/granular_dynamics.h>

#include <map>
#include <memory>
#include <string>

namespace softsand
{
  namespace core
  {
    /**
     * A scene of grains alone (simulation control/mode = granular): insert
     * or load a pack, then move it under contacts, walls and gravity until
     * the end time or until it has settled. No fluid system is built. The
     * mesh is only the grains' home for parallel distribution: cells at
     * least one contact range (2 r_max + skin) wide.
     */
    class GranularSimulator
    {
    public:
      GranularSimulator(const Parameters<3> &parameters, const MPI_Comm comm);

      void
      run();

      /// Final numbers (name -> value), as printed by the run.
      const std::map<std::string, double> &
      results() const
      {
        return last_results;
      }

      const dem::GranularDynamics &
      dynamics() const
      {
        return *dem;
      }

    private:
      void
      make_mesh(const double cell_size);

      const Parameters<3>                       &parameters;
      MPI_Comm                                   mpi_communicator;
      ConditionalOStream                         pcout;
      ConditionalOStream                         progress;
      parallel::distributed::Triangulation<3>    triangulation;
      std::unique_ptr<dem::GranularDynamics>     dem;
      std::map<std::string, double>              last_results;
    };
  } // namespace core
} // namespace softsand

#endif
