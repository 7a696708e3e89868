#include <ritr/solver/distributed_linear_system.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>

#include <stdexcept>

namespace ritr
{
  namespace TW = dealii::TrilinosWrappers;

  struct DistributedLinearSystem::Trilinos
  {
    dealii::IndexSet                    owned;  // this process's rows (Trilinos numbering)
    TW::SparsityPattern                 pattern;
    TW::SparseMatrix                    matrix;
    // MUMPS through Amesos itself rather than deal.II's SolverDirect, which analyses the
    // pattern again with every factorization: the analysis is kept while the pattern is.
    Epetra_LinearProblem                 problem;
    std::unique_ptr<Amesos_BaseSolver>   direct;
    std::unique_ptr<TW::PreconditionAMG> amg;
  };

  DistributedLinearSystem::DistributedLinearSystem(const WorkShare &share, const DistributedSolver solver)
    : share_(share)
    , solver_(solver)
    , trilinos_(std::make_unique<Trilinos>())
  {}

  DistributedLinearSystem::~DistributedLinearSystem() = default;

  void DistributedLinearSystem::build_pattern(const Eigen::SparseMatrix<double> &local_lower,
                                              const std::vector<int>            &free_entry)
  {
    const int n = static_cast<int>(local_lower.rows());
    // Rows numbered process by process, each process's in the order of the free unknowns.
    std::vector<int> count(share_.size() + 1, 0);
    for (int f = 0; f < n; ++f)
      ++count[share_.entry_owner(free_entry[f]) + 1];
    for (unsigned int r = 0; r < share_.size(); ++r)
      count[r + 1] += count[r];
    row_of_.resize(n);
    std::vector<int> next(count.begin(), count.end() - 1);
    for (int f = 0; f < n; ++f)
      row_of_[f] = next[share_.entry_owner(free_entry[f])]++;

    Trilinos &t = *trilinos_;
    t.owned     = dealii::IndexSet(n);
    t.owned.add_range(count[share_.rank()], count[share_.rank() + 1]);
    // Every row is writable: a process's cells and stencils touch rows of other processes'
    // nodes, whose entries Trilinos sends to their owners when the matrix is compressed.
    t.pattern.reinit(t.owned, t.owned, dealii::complete_index_set(n), share_.communicator());
    for (int c = 0; c < n; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(local_lower, c); it; ++it)
        {
          const auto i = row_of_[it.row()], j = row_of_[c];
          t.pattern.add(i, j);
          if (i != j)
            t.pattern.add(j, i);
        }
    t.pattern.compress();
    t.matrix.reinit(t.pattern);
    outer_.assign(local_lower.outerIndexPtr(), local_lower.outerIndexPtr() + local_lower.outerSize() + 1);
    inner_.assign(local_lower.innerIndexPtr(), local_lower.innerIndexPtr() + local_lower.nonZeros());
    ++n_patterns_;
  }

  void DistributedLinearSystem::factorize(const Eigen::SparseMatrix<double> &local_lower,
                                          const std::vector<int>            &free_entry)
  {
    const bool same_pattern =
      row_of_.size() == static_cast<std::size_t>(local_lower.rows()) &&
      outer_.size() == static_cast<std::size_t>(local_lower.outerSize() + 1) &&
      std::equal(outer_.begin(), outer_.end(), local_lower.outerIndexPtr()) &&
      inner_.size() == static_cast<std::size_t>(local_lower.nonZeros()) &&
      std::equal(inner_.begin(), inner_.end(), local_lower.innerIndexPtr());
    Trilinos  &t           = *trilinos_;
    const bool new_pattern = !share_.all(same_pattern);
    // The factorization of the last matrix goes first: MUMPS' clean-up reads the matrix's
    // maps, which a new pattern replaces.
    if (new_pattern)
      t.direct.reset();
    t.amg.reset();
    if (new_pattern)
      build_pattern(local_lower, free_entry);

    t.matrix    = 0;
    for (int c = 0; c < local_lower.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(local_lower, c); it; ++it)
        {
          const auto i = row_of_[it.row()], j = row_of_[c];
          t.matrix.add(i, j, it.value());
          if (i != j)
            t.matrix.add(j, i, it.value());
        }
    t.matrix.compress(dealii::VectorOperation::add);

    if (solver_ == DistributedSolver::direct)
      {
        if (!t.direct)
          {
            t.problem.SetOperator(const_cast<Epetra_CrsMatrix *>(&t.matrix.trilinos_matrix()));
            t.direct.reset(Amesos().Create("Amesos_Mumps", t.problem));
            if (!t.direct)
              throw std::runtime_error("Trilinos' Amesos has no MUMPS (Solver/distributed solver = direct)");
            if (const int error = t.direct->SymbolicFactorization())
              throw std::runtime_error("MUMPS' analysis failed (error " + std::to_string(error) + ")");
          }
        if (const int error = t.direct->NumericFactorization())
          throw std::runtime_error("MUMPS' factorization failed (error " + std::to_string(error) + ")");
      }
    else
      {
        // The translations are the near null space of elasticity that ML's aggregates keep.
        TW::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = false;
        data.smoother_sweeps       = 2;
        data.aggregation_threshold = 0.02;
        data.constant_modes.assign(share_.dim(), std::vector<bool>(row_of_.size(), false));
        for (std::size_t f = 0; f < row_of_.size(); ++f)
          data.constant_modes[share_.entry_component(free_entry[f])][row_of_[f]] = true;
        t.amg = std::make_unique<TW::PreconditionAMG>();
        t.amg->initialize(t.matrix, data);
      }
    ++n_factorizations_;
  }

  Eigen::VectorXd DistributedLinearSystem::solve(const Eigen::VectorXd &rhs)
  {
    Trilinos      &t = *trilinos_;
    TW::MPI::Vector b(t.owned, share_.communicator()), x(t.owned, share_.communicator());
    for (std::size_t f = 0; f < row_of_.size(); ++f)
      if (t.owned.is_element(row_of_[f]))
        b[row_of_[f]] = rhs[f];
    b.compress(dealii::VectorOperation::insert);
    if (solver_ == DistributedSolver::direct)
      {
        t.problem.SetLHS(&x.trilinos_vector());
        t.problem.SetRHS(const_cast<Epetra_MultiVector *>(static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
        const int error = t.direct->Solve();
        t.problem.SetLHS(nullptr);  // x and b end with this call
        t.problem.SetRHS(nullptr);
        if (error)
          throw std::runtime_error("MUMPS' solve failed (error " + std::to_string(error) + ")");
      }
    else
      {
        // The barrier makes the projected Hessian badly conditioned near contact: a residual of
        // 1e-10 of the right-hand side left steps inexact enough to cost a 3D ball on spikes
        // 68 Newton iterations instead of 41; at 1e-12 it takes 42, at 1e-14 41.
        dealii::SolverControl control(10000, 1e-12 * b.l2_norm());
        dealii::SolverCG<TW::MPI::Vector> cg(control);
        try
          {
            cg.solve(t.matrix, x, b, *t.amg);
          }
        catch (const dealii::SolverControl::NoConvergence &e)
          {
            throw std::runtime_error("AMG-preconditioned CG did not converge in " + std::to_string(e.last_step) +
                                     " iterations (residual " + std::to_string(e.last_residual) + ")");
          }
        cg_iterations_ += control.last_step();
      }
    Eigen::VectorXd solution = Eigen::VectorXd::Zero(rhs.size());
    for (std::size_t f = 0; f < row_of_.size(); ++f)
      if (t.owned.is_element(row_of_[f]))
        solution[f] = x[row_of_[f]];
    share_.sum(solution);  // each entry is non-zero on its owner only
    return solution;
  }
} // namespace ritr
