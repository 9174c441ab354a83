#include <softsand/base/warnings.h>
#include <softsand/fluid/block_schur_preconditioner.h>
#include <softsand/fluid/discrete_brinkman_solver.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <deal.II/base/timer.h>

#include <Amesos_Mumps.h>

#include <fstream>
#include <string>
#include <Epetra_LinearProblem.h>
#include <Epetra_Vector.h>

namespace softsand
{
  namespace fluid
  {
    DiscreteBrinkmanSolver::DiscreteBrinkmanSolver() = default;
    DiscreteBrinkmanSolver::~DiscreteBrinkmanSolver() = default;


    void
    DiscreteBrinkmanSolver::clear()
    {
      factorization.reset();
      problem.reset();
      amg.clear();
      matrix = nullptr;
    }


    namespace
    {
      /// MemAvailable of /proc/meminfo in MB; 0 where it cannot be read.
      double
      available_memory_megabytes()
      {
        std::ifstream meminfo("/proc/meminfo");
        std::string   key;
        double        kilobytes = 0;
        while (meminfo >> key >> kilobytes)
          {
            if (key == "MemAvailable:")
              return kilobytes / 1024;
            meminfo.ignore(256, '\n');
          }
        return 0;
      }
    } // namespace


    void
    DiscreteBrinkmanSolver::pin_pressure_level(TrilinosWrappers::SparseMatrix &x)
    {
      // Coupled rows: those with an off-diagonal entry. The others are the
      // constrained pressures, given a lone diagonal entry.
      const auto    range = x.local_range();
      const MPI_Comm comm = x.get_mpi_communicator();
      TrilinosWrappers::MPI::Vector coupled(x.locally_owned_range_indices(),
                                            comm);
      TrilinosWrappers::MPI::Vector row_sums(coupled);
      types::global_dof_index first = numbers::invalid_dof_index;
      for (auto i = range.first; i < range.second; ++i)
        for (auto entry = x.begin(i); entry != x.end(i); ++entry)
          if (entry->column() != i && entry->value() != 0)
            {
              coupled(i) = 1;
              first      = std::min(first, i);
              break;
            }
      coupled.compress(VectorOperation::insert);
      x.vmult(row_sums, coupled);
      double largest_ratio = 0;
      for (auto i = range.first; i < range.second; ++i)
        if (coupled(i) != 0)
          largest_ratio = std::max(largest_ratio,
                                   std::abs(row_sums(i)) / x.diag_element(i));
      largest_ratio = dealii::Utilities::MPI::max(largest_ratio, comm);
      first         = dealii::Utilities::MPI::min(first, comm);
      // Rounding leaves about 1e-14 of the diagonal in a zero row sum; a
      // pressure face leaves O(1) on the rows next to it.
      const bool free_level =
        first != numbers::invalid_dof_index && largest_ratio < 1e-8;
      if (free_level && first >= range.first && first < range.second)
        x.set(first, first, 2 * x.diag_element(first));
      x.compress(VectorOperation::insert);
    }


    void
    DiscreteBrinkmanSolver::initialize(TrilinosWrappers::SparseMatrix &x,
                                       const Method method,
                                       const double inner_tolerance)
    {
      clear();
      matrix          = &x;
      this->method    = method == Method::automatic ? Method::direct : method;
      this->tolerance = inner_tolerance;
      solves = iterations = 0;
      wall_time = 0;
      if (this->method == Method::amg_cg)
        {
          amg.initialize(x, pressure_laplace_amg_data());
          return;
        }
      pin_pressure_level(x);
      problem = std::make_unique<Epetra_LinearProblem>();
      // Amesos takes a non-const operator; it does not change it.
      problem->SetOperator(
        const_cast<Epetra_CrsMatrix *>(&x.trilinos_matrix()));
      // Debian's MUMPS orders with PORD (it has neither METIS nor SCOTCH);
      // X is symmetric, but Amesos passes both triangles: general LU.
      auto           mumps = std::make_unique<Amesos_Mumps>(*problem);
      const MPI_Comm comm = x.get_mpi_communicator();
      // After the analysis MUMPS knows the memory its factors will take
      // (INFO(15), MB on this rank): one that does not fit is refused
      // before it is made, not met by the kernel's OOM killer.
      const bool analysed = mumps->SymbolicFactorization() == 0;
      const double estimate_mb = analysed ? mumps->GetINFO()[14] : 0.;
      // MemAvailable is the node's: shared by the ranks on it.
      MPI_Comm node;
      MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
      int ranks_on_node = 1;
      MPI_Comm_size(node, &ranks_on_node);
      MPI_Comm_free(&node);
      const double available_mb = available_memory_megabytes() / ranks_on_node;
      const bool fits = dealii::Utilities::MPI::logical_or(
                          available_mb > 0 && estimate_mb > 0.5 * available_mb,
                          comm) == false;
      const bool factorized =
        analysed && fits && mumps->NumericFactorization() == 0;
      if (!factorized)
        {
          // Factors that would not fit, or a singular X that the pin does
          // not cure (a mesh so coarse that B has fewer free velocities
          // than pressures: spurious pressure modes). CG needs only linear
          // memory and copes with a consistent singular system.
          const std::string why =
            !fits ? "MUMPS estimates " + std::to_string(long(estimate_mb)) +
                      " MB for the factors on a rank with " +
                      std::to_string(long(available_mb)) +
                      " MB available (its share of the node's)" :
                    "MUMPS could not factorize it (INFOG(1) = " +
                      std::to_string(mumps->GetINFOG()[0]) +
                      "; -10: singular, e.g. a mesh too coarse for its walls)";
          base::warn_once("direct X fallback",
                          "The pressure matrix X = B D^-1 B^T + C of the Schur "
                          "approximation is not factorized: " + why +
                            ". 'fluid solver/schur inner solver' falls back to "
                            "amg cg for this matrix.",
                          comm);
          mumps.reset(); // before the problem it refers to
          problem.reset();
          this->method = Method::amg_cg;
          amg.initialize(x, pressure_laplace_amg_data());
          return;
        }
      factorization = std::move(mumps);
    }


    void
    DiscreteBrinkmanSolver::solve_direct(double *dst, const double *src) const
    {
      const Epetra_Map &map = matrix->trilinos_matrix().DomainMap();
      Epetra_Vector     x(View, map, dst);
      Epetra_Vector     b(View, map, const_cast<double *>(src));
      problem->SetLHS(&x);
      problem->SetRHS(&b);
      Timer timer;
      AssertThrow(factorization->Solve() == 0,
                  ExcMessage("MUMPS failed in a solve with X."));
      wall_time += timer.wall_time();
      ++solves;
    }


    template <typename VectorType>
    void
    DiscreteBrinkmanSolver::solve_by_amg_cg(VectorType       &dst,
                                            const VectorType &src) const
    {
      Timer                timer;
      ReductionControl     control(200, 1e-300, tolerance, false, false);
      SolverCG<VectorType> cg(control);
      dst = 0;
      try
        {
          cg.solve(*matrix, dst, src, amg);
        }
      catch (const SolverControl::NoConvergence &)
        {}
      iterations += control.last_step();
      wall_time += timer.wall_time();
      ++solves;
    }


    void
    DiscreteBrinkmanSolver::solve(TrilinosWrappers::MPI::Vector       &dst,
                                  const TrilinosWrappers::MPI::Vector &src) const
    {
      if (method == Method::direct)
        solve_direct(&dst.trilinos_vector()[0][0],
                     &src.trilinos_vector()[0][0]);
      else
        solve_by_amg_cg(dst, src);
    }


    void
    DiscreteBrinkmanSolver::solve(
      LinearAlgebra::distributed::Vector<double>       &dst,
      const LinearAlgebra::distributed::Vector<double> &src) const
    {
      if (method == Method::direct)
        solve_direct(dst.begin(), src.begin());
      else
        solve_by_amg_cg(dst, src);
    }
  } // namespace fluid
} // namespace softsand
