#include <ritr/solver/reduced_system.h>

#include <algorithm>

namespace ritr
{
  void ReducedSystem::build_pattern(const Triplets &hessian,
                                    const std::vector<int> &free_index, const int n_free)
  {
    Triplets lower;
    lower.reserve(hessian.size());
    rows_.resize(hessian.size());
    columns_.resize(hessian.size());
    for (std::size_t i = 0; i < hessian.size(); ++i)
      {
        rows_[i]    = hessian[i].row();
        columns_[i] = hessian[i].col();
        const int r = free_index[rows_[i]], c = free_index[columns_[i]];
        if (r >= 0 && c >= 0 && r >= c)
          lower.emplace_back(r, c, 0.0);
      }
    // The diagonal is always in the pattern: an unknown without any Hessian entry (a flat
    // outer direction) then gets a structural zero that the shift can regularise, where an
    // empty matrix would be rejected by CHOLMOD.
    for (int i = 0; i < n_free; ++i)
      lower.emplace_back(i, i, 0.0);
    free_index_ = free_index;
    matrix_.resize(n_free, n_free);
    matrix_.setFromTriplets(lower.begin(), lower.end());
    matrix_.makeCompressed();
    slot_.resize(hessian.size());
    coupled_.clear();
    const int *outer = matrix_.outerIndexPtr(), *inner = matrix_.innerIndexPtr();
    for (std::size_t i = 0; i < hessian.size(); ++i)
      {
        const int r = free_index[rows_[i]], c = free_index[columns_[i]];
        if (r >= 0 && c >= 0)
          slot_[i] = r >= c ? static_cast<int>(std::lower_bound(inner + outer[c], inner + outer[c + 1], r) - inner) : -1;
        else
          slot_[i] = r >= 0 ? -2 - r : -1;
        if (slot_[i] <= -2)
          coupled_.push_back(i);
      }
  }

  void ReducedSystem::assemble(const Triplets &hessian, const std::vector<int> &free_index,
                               const int n_free, const Eigen::VectorXd &prescribed_step, Eigen::VectorXd &rhs)
  {
    // The structure is checked while the values are added (one pass over the list); on a
    // change the pattern is rebuilt and the values added again.
    const bool same = hessian.size() == rows_.size() && free_index == free_index_ && fill(hessian, true);
    if (!same)
      {
        build_pattern(hessian, free_index, n_free);
        fill(hessian, false);
      }
    for (const std::size_t i : coupled_)
      rhs[-2 - slot_[i]] -= hessian[i].value() * prescribed_step[columns_[i]];
  }

  bool ReducedSystem::fill(const Triplets &hessian, const bool check_structure)
  {
    double *values = matrix_.valuePtr();
    std::fill(values, values + matrix_.nonZeros(), 0.0);
    for (std::size_t i = 0; i < hessian.size(); ++i)
      {
        if (check_structure && (hessian[i].row() != rows_[i] || hessian[i].col() != columns_[i]))
          return false;
        if (const int s = slot_[i]; s >= 0)
          values[s] += hessian[i].value();
      }
    return true;
  }

  void ReducedSystem::assemble_changed(const ReducedSystem &base, const TripletChanges &changes)
  {
    matrix_     = base.matrix_;  // the storage is reused while the size holds
    free_index_ = base.free_index_;
    rows_.clear();  // not assembled from a triplet list of its own
    columns_.clear();
    coupled_.clear();
    double *values = matrix_.valuePtr();
    for (const auto &[position, value] : changes)
      if (const int s = base.slot_[position]; s >= 0)
        values[s] += value;  // upper-triangle and prescribed entries have no slot
  }
} // namespace ritr
