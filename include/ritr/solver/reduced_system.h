#pragma once
// The Newton system over the free unknowns: the lower triangle of the Hessian's free-free
// block as a compressed matrix, with the coupling to prescribed entries moved to the
// right-hand side. While the Hessian's triplet list keeps its sequence of (row, column)
// pairs -- every iteration whose contact set did not change -- the matrix's pattern is
// reused and each triplet is added straight into its slot, in the same order as
// setFromTriplets would sum it (the same values, bit for bit).
#include <ritr/common/triplets.h>

#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  class ReducedSystem
  {
  public:
    // `free_index[i]`: position of unknown i among the free ones, -1 if prescribed.
    // `prescribed_step`: the step of the prescribed entries (others ignored); `rhs` (size
    // n_free, holding -g on entry) gets -H_fk * prescribed_step added.
    void assemble(const Triplets &hessian, const std::vector<int> &free_index,
                  int n_free, const Eigen::VectorXd &prescribed_step, Eigen::VectorXd &rhs);

    // The matrix of `base` plus `correction`, whose entries lie in base's pattern (the
    // projected Hessian as the exact one plus the projection's change on a few stencils).
    void assemble_sum(const ReducedSystem &base, const Triplets &correction);

    const Eigen::SparseMatrix<double> &matrix() const { return matrix_; }

  private:
    bool same_structure(const Triplets &hessian, const std::vector<int> &free_index) const;
    void build_pattern(const Triplets &hessian, const std::vector<int> &free_index,
                       int n_free);

    Eigen::SparseMatrix<double> matrix_;
    std::vector<int>            rows_, columns_, free_index_;
    // Per triplet: >= 0 its slot in matrix_.valuePtr(); -1 not used (upper triangle or a
    // prescribed row); <= -2 a free row -2 - slot coupled to a prescribed column.
    std::vector<int> slot_;
  };
} // namespace ritr
