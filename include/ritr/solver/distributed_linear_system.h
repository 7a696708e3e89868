#pragma once
// The Newton system of a run shared among MPI processes (parallel/work_share.h), solved by
// Trilinos through deal.II's wrappers: each process hands in its part of the matrix (the
// lower triangle of the free-free block over the cells and contact stencils it assembled;
// the parts sum to the matrix), the rows of the nodes it owns make its block of a
// distributed Trilinos matrix, and the solution comes back whole on every process.
//
// Two solvers: a direct one (Amesos with MUMPS, a distributed LU), or conjugate gradients
// preconditioned by ML's algebraic multigrid with the translations as its near null space.
// The projected Newton matrix is symmetric positive definite, which both need. With the
// direct solver, its solves also precondition the trust region's CG on the exact Hessian.
#include <ritr/parallel/work_share.h>
#include <ritr/solver/distributed_solver.h>

#include <Eigen/Sparse>

#include <memory>
#include <vector>

namespace ritr
{
  class DistributedLinearSystem
  {
  public:
    DistributedLinearSystem(const WorkShare &share, DistributedSolver solver);
    ~DistributedLinearSystem();

    // `local_lower`: this process's part of the lower triangle of the free-free matrix;
    // `free_entry[f]`: the state entry of free unknown f (always of a body node: obstacle
    // vertices are prescribed).
    // The Trilinos pattern is kept while no process's local pattern changes.
    void factorize(const Eigen::SparseMatrix<double> &local_lower, const std::vector<int> &free_entry);
    // `rhs` whole and the same on every process; the solution whole on every process.
    Eigen::VectorXd solve(const Eigen::VectorXd &rhs);

    unsigned int n_symbolic_analyses() const { return n_patterns_; }
    unsigned int n_factorizations() const { return n_factorizations_; }
    unsigned int cg_iterations() const { return cg_iterations_; }  // AMG: over all solves

  private:
    struct Trilinos;  // the deal.II/Trilinos objects, kept out of this header
    void build_pattern(const Eigen::SparseMatrix<double> &local_lower, const std::vector<int> &free_entry);

    const WorkShare          &share_;
    const DistributedSolver   solver_;
    std::unique_ptr<Trilinos> trilinos_;
    // Free unknown -> its row in the Trilinos numbering, where each process's rows are one
    // contiguous range (so that its maps are the plain contiguous ones).
    std::vector<int>          row_of_;
    std::vector<int>          outer_, inner_;  // the local pattern the Trilinos one was built for
    unsigned int              n_patterns_ = 0, n_factorizations_ = 0, cg_iterations_ = 0;
  };
} // namespace ritr
