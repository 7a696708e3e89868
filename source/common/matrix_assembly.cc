#include <ritr/common/matrix_assembly.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace ritr
{
  template <int dim>
  void MatrixAssembly<dim>::clear()
  {
    std::fill(values_.begin(), values_.end(), 0.0);
    triplets_.clear();
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
