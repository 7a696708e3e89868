#include <ritr/common/matrix_assembly.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace ritr
{
  template <int dim>
  void MatrixAssembly<dim>::clear()
  {
    constexpr int n = cell_dofs;
    std::fill(values_.begin(), values_.end(), 0.0);
    triplets_.clear();
    for (std::size_t c = 0; c < changed_.size(); ++c)
      if (changed_[c])
        {
          std::fill_n(changes_.data() + c * n * n, n * n, 0.0);
          changed_[c] = 0;
        }
    triplet_changes_.clear();
  }

  template <int dim>
  void MatrixAssembly<dim>::use_change_blocks()
  {
    if (changes_.empty())
      {
        changes_.assign(cells_->size() * cell_dofs * cell_dofs, 0.0);
        changed_.assign(cells_->size(), 0);
      }
  }

  template <int dim>
  void MatrixAssembly<dim>::change_triplets(const std::size_t first, const Triplets &before, const Triplets &after,
                                            const double scale)
  {
    for (std::size_t i = 0; i < before.size(); ++i)
      if (after[i].value() != before[i].value())
        triplet_changes_.emplace_back(first + i, scale * (after[i].value() - before[i].value()));
  }

  template <int dim>
  void MatrixAssembly<dim>::change_by(const MatrixAssembly &before, const MatrixAssembly &after, const std::size_t first)
  {
    constexpr int n = cell_dofs;
    if (before.triplets_.size() != after.triplets_.size() || before.values_.size() != after.values_.size())
      throw std::logic_error("MatrixAssembly::change_by: the two assemblies differ in structure");
    if (!after.values_.empty())
      {
        use_change_blocks();
        for (std::size_t c = 0; c < cells_->size(); ++c)
          {
            const auto b = Eigen::Map<const Eigen::Matrix<double, n, n>>(before.values_.data() + c * n * n);
            const auto a = Eigen::Map<const Eigen::Matrix<double, n, n>>(after.values_.data() + c * n * n);
            if (a != b)
              change_block(c) += a - b;
          }
      }
    change_triplets(first, before.triplets_, after.triplets_, 1.0);
  }

  template <int dim>
  void MatrixAssembly<dim>::append_changes(const std::size_t offset, TripletChanges &out) const
  {
    constexpr int     n     = cell_dofs;
    const std::size_t cells = values_.empty() ? 0 : cells_->size();
    for (std::size_t c = 0; c < changed_.size(); ++c)
      if (changed_[c])
        {
          // Entry (i, j) of the block is triplet i * n + j of the cell (append_block).
          const double *block = changes_.data() + c * n * n;
          for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
              out.emplace_back(offset + c * n * n + i * n + j, block[j * n + i]);
        }
    for (const auto &[position, value] : triplet_changes_)
      out.emplace_back(offset + cells * n * n + position, value);
  }

  template <int dim>
  void MatrixAssembly<dim>::append_block(const Cell &cell, const double *block, Eigen::Triplet<double> *out)
  {
    constexpr int n = cell_dofs;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        *out++ = Eigen::Triplet<double>(cell[i / dim] * dim + i % dim, cell[j / dim] * dim + j % dim, block[j * n + i]);
  }

  template <int dim>
  void MatrixAssembly<dim>::append_to(Triplets &out) const
  {
    constexpr int     n      = cell_dofs;
    const std::size_t offset = out.size();
    const std::size_t cells  = values_.empty() ? 0 : cells_->size();
    out.resize(offset + cells * n * n);
    // Every cell writes its own slice of the list, so the scatter runs in parallel.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 256), [&](const tbb::blocked_range<std::size_t> &range) {
      for (std::size_t c = range.begin(); c != range.end(); ++c)
        append_block((*cells_)[c], values_.data() + c * n * n, out.data() + offset + c * n * n);
    });
    out.insert(out.end(), triplets_.begin(), triplets_.end());
  }

  template class MatrixAssembly<1>;
  template class MatrixAssembly<2>;
  template class MatrixAssembly<3>;
} // namespace ritr
