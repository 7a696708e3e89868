#pragma once
// The Newton system over the free unknowns: the lower triangle of the Hessian's free-free
// block as a compressed matrix, with the coupling to prescribed entries moved to the
// right-hand side. The matrix's pattern is kept while the Hessian's list gives the same one:
// each triplet is added straight into its slot, in the same order as setFromTriplets would
// sum it (the same values, bit for bit). Where a list departs from the last one's sequence of
// (row, column) pairs (a changed contact set), only its rest is looked up in the pattern, and
// the pattern is rebuilt only when the list's own pattern differs from it.
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

    // The matrix `base` was last assembled to, from the same triplet list with `changes` to
    // its values (the projected Hessian from the exact one's list).
    void assemble_changed(const ReducedSystem &base, const TripletChanges &changes);

    const Eigen::SparseMatrix<double> &matrix() const { return matrix_; }

  private:
    void build_pattern(const Triplets &hessian, const std::vector<int> &free_index,
                       int n_free);
    // Slots of the triplets from `first` on in the current pattern; false if one is missing.
    bool map_into_pattern(const Triplets &hessian, std::size_t first);
    // True if every off-diagonal entry of the pattern has a triplet (no leftover entries).
    bool pattern_is_exact() const;
    void clear_values();
    // Adds the values of the leading triplets whose (row, column) match the last list's;
    // returns how many did.
    std::size_t add_matching(const Triplets &hessian);
    void        add_values(const Triplets &hessian, std::size_t first);

    Eigen::SparseMatrix<double> matrix_;
    std::vector<int>            rows_, columns_, free_index_;
    // Per triplet: >= 0 its slot in matrix_.valuePtr(); -1 not used (upper triangle or a
    // prescribed row); <= -2 a free row -2 - slot coupled to a prescribed column.
    std::vector<int>         slot_;
    std::vector<std::size_t> coupled_;  // the triplets whose slot is <= -2
  };
} // namespace ritr
