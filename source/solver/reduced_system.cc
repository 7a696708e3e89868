#include <ritr/solver/reduced_system.h>

#include <algorithm>

namespace ritr
{
  void ReducedSystem::build_pattern(const Triplets &hessian,
                                    const std::vector<int> &free_index, const int n_free)
  {
    Triplets lower;
    lower.reserve(hessian.size());
    for (const auto &t : hessian)
      {
        const int r = free_index[t.row()], c = free_index[t.col()];
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
    rows_.clear();
    columns_.clear();
    slot_.clear();
    coupled_.clear();
    map_into_pattern(hessian, 0);
  }

  bool ReducedSystem::map_into_pattern(const Triplets &hessian, const std::size_t first)
  {
    rows_.resize(hessian.size());
    columns_.resize(hessian.size());
    slot_.resize(hessian.size());
    coupled_.erase(std::lower_bound(coupled_.begin(), coupled_.end(), first), coupled_.end());
    const int *outer = matrix_.outerIndexPtr(), *inner = matrix_.innerIndexPtr();
    for (std::size_t i = first; i < hessian.size(); ++i)
      {
        rows_[i]    = hessian[i].row();
        columns_[i] = hessian[i].col();
        const int r = free_index_[rows_[i]], c = free_index_[columns_[i]];
        if (r >= 0 && c >= 0)
          {
            if (r < c)
              slot_[i] = -1;
            else
              {
                const int *end = inner + outer[c + 1], *found = std::lower_bound(inner + outer[c], end, r);
                if (found == end || *found != r)
                  return false;  // an entry the pattern lacks
                slot_[i] = static_cast<int>(found - inner);
              }
          }
        else
          slot_[i] = r >= 0 ? -2 - r : -1;
        if (slot_[i] <= -2)
          coupled_.push_back(i);
      }
    return true;
  }

  bool ReducedSystem::pattern_is_exact() const
  {
    // Every off-diagonal slot must be hit by a triplet: a slot left over from an earlier list
    // would be a structural zero that a fresh build lacks (and CHOLMOD's ordering would see).
    std::vector<char> hit(static_cast<std::size_t>(matrix_.nonZeros()), 0);
    for (const int s : slot_)
      if (s >= 0)
        hit[s] = 1;
    const int *outer = matrix_.outerIndexPtr(), *inner = matrix_.innerIndexPtr();
    for (int c = 0; c < matrix_.outerSize(); ++c)
      for (int s = outer[c]; s < outer[c + 1]; ++s)
        if (!hit[s] && inner[s] != c)
          return false;
    return true;
  }

  void ReducedSystem::assemble(const Triplets &hessian, const std::vector<int> &free_index,
                               const int n_free, const Eigen::VectorXd &prescribed_step, Eigen::VectorXd &rhs)
  {
    // The structure is checked while the values are added (one pass over the list). Where the
    // list departs from the last one -- the contact set changed, usually behind the
    // unchanged elastic part -- the rest of the list is looked up in the current pattern,
    // which is rebuilt only if the new list's pattern differs from it.
    if (free_index != free_index_ || matrix_.rows() != n_free)
      build_pattern(hessian, free_index, n_free);
    clear_values();
    const std::size_t same = add_matching(hessian);
    if (same < hessian.size() || same < rows_.size())
      {
        if (map_into_pattern(hessian, same) && pattern_is_exact())
          add_values(hessian, same);
        else
          {
            build_pattern(hessian, free_index, n_free);
            clear_values();
            add_values(hessian, 0);
          }
      }
    for (const std::size_t i : coupled_)
      rhs[-2 - slot_[i]] -= hessian[i].value() * prescribed_step[columns_[i]];
  }

  void ReducedSystem::clear_values()
  {
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
  }

  std::size_t ReducedSystem::add_matching(const Triplets &hessian)
  {
    double     *values = matrix_.valuePtr();
    const auto  n      = std::min(hessian.size(), rows_.size());
    std::size_t i      = 0;
    for (; i < n && hessian[i].row() == rows_[i] && hessian[i].col() == columns_[i]; ++i)
      if (const int s = slot_[i]; s >= 0)
        values[s] += hessian[i].value();
    return i;
  }

  void ReducedSystem::add_values(const Triplets &hessian, const std::size_t first)
  {
    double *values = matrix_.valuePtr();
    for (std::size_t i = first; i < hessian.size(); ++i)
      if (const int s = slot_[i]; s >= 0)
        values[s] += hessian[i].value();
  }

  void ReducedSystem::assemble_changed(const ReducedSystem &base, const TripletChanges &changes)
  {
    matrix_     = base.matrix_;  // the storage is reused while the size holds
    free_index_ = base.free_index_;
    rows_.clear();  // not assembled from a triplet list of its own
    columns_.clear();
    slot_.clear();
    coupled_.clear();
    double *values = matrix_.valuePtr();
    for (const auto &[position, value] : changes)
      if (const int s = base.slot_[position]; s >= 0)
        values[s] += value;  // upper-triangle and prescribed entries have no slot
  }
} // namespace ritr
