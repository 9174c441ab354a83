#include <softsand/fluid/block_schur_preconditioner.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/trilinos_index_access.h>

#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

namespace softsand
{
  namespace fluid
  {
    namespace
    {
      /// Make the pressure matrix @p x regular for AMG and CG: negative
      /// diagonals (constraint rows of -C) flipped, zero diagonals (rows
      /// that nothing couples: constrained pressures) set to the mean.
      void
      make_pressure_diagonal_regular(TrilinosWrappers::SparseMatrix &x)
      {
        const auto range = x.local_range();
        double     sum = 0, count = 0;
        for (auto i = range.first; i < range.second; ++i)
          if (x.diag_element(i) > 0)
            {
              sum += x.diag_element(i);
              ++count;
            }
        const MPI_Comm comm = x.get_mpi_communicator();
        const double   mean = Utilities::MPI::sum(sum, comm) /
                            std::max(1., Utilities::MPI::sum(count, comm));
        for (auto i = range.first; i < range.second; ++i)
          {
            const double d = x.diag_element(i);
            if (d < 0)
              x.set(i, i, -d);
            else if (!(d > 0))
              x.set(i, i, mean);
          }
        x.compress(VectorOperation::insert);
      }


      /**
       * X = B D^-1 B^T + C of the assembled saddle-point matrix
       * [A B^T; B -C], D = diag(A), with a regular diagonal on every row;
       * returns D^-1 in @p inverse.
       */
      void
      build_discrete_brinkman(
        const TrilinosWrappers::BlockSparseMatrix &system_matrix,
        TrilinosWrappers::SparseMatrix            &discrete_brinkman,
        TrilinosWrappers::MPI::Vector             &inverse)
      {
        const auto &a = system_matrix.block(0, 0);
        inverse.reinit(a.locally_owned_domain_indices(),
                       a.get_mpi_communicator());
        for (const auto i : inverse.locally_owned_elements())
          {
            const double d = a.diag_element(i);
            inverse(i)     = d > 0 ? 1. / d : 0.;
          }
        inverse.compress(VectorOperation::insert);
        // The divergence rows times D^-1 times the gradient columns (the
        // blocks carry the same sign).
        TrilinosWrappers::SparseMatrix product;
        system_matrix.block(1, 0).mmult(product,
                                        system_matrix.block(0, 1),
                                        inverse);
        discrete_brinkman_from_product(product,
                                       &system_matrix.block(1, 1),
                                       discrete_brinkman);
      }
    } // namespace


    void
    discrete_brinkman_from_product(const TrilinosWrappers::SparseMatrix &product,
                                   const TrilinosWrappers::SparseMatrix *c,
                                   TrilinosWrappers::SparseMatrix       &x)
    {
      // The pressure block is -C (rigid-node smoothing) on coupled rows
      // and the positive constraint diagonal on constrained rows, which
      // have empty B rows: subtract it, then make the constrained
      // diagonals positive again and give zero diagonals the mean, so
      // that AMG and CG see a regular positive matrix (these rows are
      // overwritten by the constraints). Without C, an explicit zero
      // diagonal is added first: the product has no entry at all in an
      // empty B row, and a row missing its diagonal cannot be given one
      // later (X stayed singular there, and the inner CG on it ran to its
      // iteration bound on every penalized pack).
      const Epetra_CrsMatrix &p = product.trilinos_matrix();
      Epetra_CrsMatrix        diagonal(Copy, p.RowMap(), 1);
      for (int l = 0; l < p.RowMap().NumMyElements(); ++l)
        {
          int          row  = p.RowMap().GID(l);
          const double zero = 0;
          diagonal.InsertGlobalValues(row, 1, &zero, &row);
        }
      diagonal.FillComplete(p.DomainMap(), p.RangeMap());
      const Epetra_CrsMatrix &second =
        c == nullptr ? diagonal : c->trilinos_matrix();

      Epetra_CrsMatrix *sum  = nullptr;
      int               ierr = EpetraExt::MatrixMatrix::Add(
        p, false, 1., second, false, -1., sum);
      AssertThrow(ierr == 0 && sum != nullptr,
                  ExcMessage("EpetraExt could not add the pressure block "
                             "to B D^-1 B^T."));
      sum->FillComplete(p.DomainMap(), p.RangeMap());
      if (c != nullptr)
        {
          // C's pattern need not hold every diagonal either.
          Epetra_CrsMatrix *with_diagonal = nullptr;
          ierr = EpetraExt::MatrixMatrix::Add(
            *sum, false, 1., diagonal, false, 1., with_diagonal);
          AssertThrow(ierr == 0 && with_diagonal != nullptr,
                      ExcMessage("EpetraExt could not add a diagonal to "
                                 "B D^-1 B^T + C."));
          with_diagonal->FillComplete(p.DomainMap(), p.RangeMap());
          delete sum;
          sum = with_diagonal;
        }
      x.reinit(*sum);
      delete sum;
      make_pressure_diagonal_regular(x);
    }


    namespace
    {
      /// The local column indices of @p from as local columns of @p into
      /// (whose pattern holds @p from's), -1 for a column of @p from's
      /// column map that none of its entries uses (deal.II's maps can hold
      /// every relevant column).
      std::vector<int>
      columns_in(const Epetra_CrsMatrix &from, const Epetra_CrsMatrix &into)
      {
        std::vector<int> columns(from.ColMap().NumMyElements());
        for (unsigned int l = 0; l < columns.size(); ++l)
          columns[l] =
            into.ColMap().LID(TrilinosWrappers::global_column_index(from, l));
        return columns;
      }


      /// Add @p factor times the entries of @p from to @p into, whose
      /// pattern holds @p from's, through @p columns (columns_in()).
      void
      add_in_pattern(const Epetra_CrsMatrix &from,
                     const double            factor,
                     const std::vector<int> &columns,
                     Epetra_CrsMatrix       &into)
      {
        std::vector<double> values;
        std::vector<int>    into_columns;
        for (int row = 0; row < from.NumMyRows(); ++row)
          {
            int     n_entries;
            double *from_values;
            int    *from_columns;
            from.ExtractMyRowView(row, n_entries, from_values, from_columns);
            values.resize(n_entries);
            into_columns.resize(n_entries);
            for (int e = 0; e < n_entries; ++e)
              {
                values[e]       = factor * from_values[e];
                into_columns[e] = columns[from_columns[e]];
              }
            const int ierr = into.SumIntoMyValues(
              into.RowMap().LID(TrilinosWrappers::global_row_index(from, row)),
              n_entries,
              values.data(),
              into_columns.data());
            AssertThrow(ierr == 0,
                        ExcMessage("B D^-1 B^T or the pressure block has an "
                                   "entry outside the pressure matrix's "
                                   "pattern."));
          }
      }
    } // namespace


    bool
    DiscreteBrinkmanProduct::initialized() const
    {
      return product.m() > 0;
    }


    void
    DiscreteBrinkmanProduct::initialize(
      const TrilinosWrappers::SparseMatrix &divergence,
      const TrilinosWrappers::SparseMatrix &gradient,
      const TrilinosWrappers::SparseMatrix *c,
      TrilinosWrappers::SparseMatrix       &x)
    {
      divergence.mmult(product, gradient);
      discrete_brinkman_from_product(product, c, x);
      // EpetraExt's product into a filled matrix fails (an assertion in
      // Epetra's map comparison) where a rank owns no row: such meshes
      // form X anew at every step.
      every_rank_has_rows =
        Utilities::MPI::min(product.trilinos_matrix().NumMyRows() > 0 ? 1 : 0,
                            x.get_mpi_communicator()) == 1;
      product_columns =
        columns_in(product.trilinos_matrix(), x.trilinos_matrix());
      if (c != nullptr)
        c_columns = columns_in(c->trilinos_matrix(), x.trilinos_matrix());
    }


    void
    DiscreteBrinkmanProduct::refresh(
      const TrilinosWrappers::SparseMatrix &divergence,
      const TrilinosWrappers::SparseMatrix &gradient,
      const TrilinosWrappers::SparseMatrix *c,
      TrilinosWrappers::SparseMatrix       &x)
    {
      if (!every_rank_has_rows)
        {
          initialize(divergence, gradient, c, x);
          return;
        }
      // deal.II hands out the Epetra matrices read-only; their values are
      // ours. The product must keep exactly its first pattern: EpetraExt
      // rewrites the column indices too.
      Epetra_CrsMatrix &p =
        const_cast<Epetra_CrsMatrix &>(product.trilinos_matrix());
      const int ierr =
        EpetraExt::MatrixMatrix::Multiply(divergence.trilinos_matrix(),
                                          false,
                                          gradient.trilinos_matrix(),
                                          false,
                                          p);
      AssertThrow(ierr == 0,
                  ExcMessage("EpetraExt could not form B D^-1 B^T again."));
      Epetra_CrsMatrix &matrix =
        const_cast<Epetra_CrsMatrix &>(x.trilinos_matrix());
      matrix.PutScalar(0.);
      add_in_pattern(p, 1., product_columns, matrix);
      if (c != nullptr)
        add_in_pattern(c->trilinos_matrix(), -1., c_columns, matrix);
      make_pressure_diagonal_regular(x);
    }


    TrilinosWrappers::PreconditionAMG::AdditionalData
    pressure_laplace_amg_data()
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      return data;
    }


    BlockSchurPreconditioner::BlockSchurPreconditioner(
      const TrilinosWrappers::BlockSparseMatrix &system_matrix,
      const TrilinosWrappers::BlockSparseMatrix &pressure_mass_matrix,
      const TrilinosWrappers::BlockSparseMatrix *pressure_laplace_matrix,
      const std::vector<std::vector<bool>>      &velocity_constant_modes,
      const unsigned int                         amg_sweeps,
      const std::string                         &velocity_smoother,
      const SolverParameters::Schur              schur,
      const double                               inner_tolerance,
      const bool                                 direct_velocity_solve,
      const SolverParameters::SchurInnerSolver   inner_solver,
      const bool                                 smoothed_aggregation)
      : system_matrix(system_matrix)
      , velocity_smoother(velocity_smoother)
      , schur(schur)
      , use_laplace(pressure_laplace_matrix != nullptr ||
                    schur == SolverParameters::Schur::discrete_brinkman ||
                    schur == SolverParameters::Schur::least_squares_commutator)
    {
      if (direct_velocity_solve)
        {
          velocity_direct =
            std::make_unique<TrilinosWrappers::SolverDirect>(direct_control);
          velocity_direct->initialize(system_matrix.block(0, 0));
        }
      else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.constant_modes        = velocity_constant_modes;
        data.elliptic              = true;
        data.higher_order_elements = true;
        data.smoother_sweeps       = amg_sweeps;
        data.aggregation_threshold = 0.02;
        data.smoother_type         = this->velocity_smoother.c_str();
        Teuchos::ParameterList              ml_parameters;
        std::unique_ptr<Epetra_MultiVector> distributed_modes;
        data.set_parameters(ml_parameters,
                            distributed_modes,
                            system_matrix.block(0, 0));
        // Plain aggregation: the block's mass or Brinkman term makes it
        // well conditioned enough that the denser smoothed coarse levels
        // cost more setup time and memory than they save in iterations.
        if (!smoothed_aggregation)
          ml_parameters.set("aggregation: damping factor", 0.);
        velocity_amg.initialize(system_matrix.block(0, 0), ml_parameters);
      }
      if (schur != SolverParameters::Schur::least_squares_commutator)
        pressure_mass_ilu.initialize(pressure_mass_matrix.block(1, 1));
      if (use_laplace)
        {
          const auto data = pressure_laplace_amg_data();
          if (pressure_laplace_matrix == nullptr)
            {
              build_discrete_brinkman(system_matrix,
                                      discrete_brinkman,
                                      inverse_velocity_diagonal);
              discrete_brinkman_inverse.initialize(discrete_brinkman,
                                                   inner_solver,
                                                   inner_tolerance);
            }
          else
            pressure_laplace_amg.initialize(pressure_laplace_matrix->block(1, 1),
                                            data);
        }
      tmp_u.reinit(system_matrix.block(0, 0).locally_owned_range_indices(),
                   system_matrix.get_mpi_communicator());
      tmp_u2.reinit(tmp_u);
      tmp_p.reinit(system_matrix.block(1, 1).locally_owned_range_indices(),
                   system_matrix.get_mpi_communicator());
      tmp_p2.reinit(tmp_p);
    }


    void
    BlockSchurPreconditioner::vmult(BlockVector &dst, const BlockVector &src) const
    {
      if (schur == SolverParameters::Schur::least_squares_commutator)
        {
          // dst_p = -X^-1 (B D^-1 A D^-1 B^T) X^-1 src_p.
          discrete_brinkman_inverse.solve(tmp_p, src.block(1));
          system_matrix.block(0, 1).vmult(tmp_u, tmp_p);
          tmp_u.scale(inverse_velocity_diagonal);
          system_matrix.block(0, 0).vmult(tmp_u2, tmp_u);
          tmp_u2.scale(inverse_velocity_diagonal);
          system_matrix.block(1, 0).vmult(tmp_p2, tmp_u2);
          // The pressure block (-C, constraint diagonals) in the middle
          // too (Elman et al.'s stabilized commutator): pressure modes that
          // no free velocity sees (B^T p = 0: constrained rows, pockets that
          // only the rigid-node smoothing couples) then get S^-1 = C^-1
          // exactly. Without it FGMRES stalled on the second coupled step of
          // the small Hele-Shaw cell (doc/notes/solver_study.md).
          system_matrix.block(1, 1).vmult(dst.block(1), tmp_p);
          tmp_p2 -= dst.block(1);
          discrete_brinkman_inverse.solve(dst.block(1), tmp_p2);
          dst.block(1) *= -1.;
        }
      else
        {
          // Pressure: dst_p = -S^-1 src_p.
          pressure_mass_ilu.vmult(dst.block(1), src.block(1));
          if (use_laplace)
            {
              if (discrete_brinkman.m() > 0)
                discrete_brinkman_inverse.solve(tmp_p, src.block(1));
              else
                pressure_laplace_amg.vmult(tmp_p, src.block(1));
              dst.block(1) += tmp_p;
            }
          dst.block(1) *= -1.;
        }
      // Velocity: dst_u = A^-1 (src_u - B^T dst_p).
      system_matrix.block(0, 1).vmult(tmp_u, dst.block(1));
      tmp_u.sadd(-1., 1., src.block(0));
      if (velocity_direct)
        velocity_direct->solve(dst.block(0), tmp_u);
      else
        velocity_amg.vmult(dst.block(0), tmp_u);
    }
  } // namespace fluid
} // namespace softsand
