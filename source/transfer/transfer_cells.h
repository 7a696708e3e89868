#pragma once
// What the two integrations of TransferOperator (transfer_operator.cc: the shared interface
// and the quadrature; exact_transfer.cc: the overlap polygons) share: the per-cell types and
// loops. Internal to source/transfer.
#include <ritr/transfer/transfer_operator.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace ritr::transfer
{
  namespace cells
  {
    template <int dim>
    using CellVector = Eigen::Matrix<double, dim *(dim + 1), 1>;
    template <int dim>
    using CellMatrix = Eigen::Matrix<double, dim *(dim + 1), dim *(dim + 1)>;

    constexpr std::size_t grain_size = 64;

    // Runs f(c) for every cell in parallel; each cell writes only its own output slots.
    template <typename F>
    void for_each_cell(const std::size_t n_cells, F &&f)
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_cells, grain_size),
                        [&](const tbb::blocked_range<std::size_t> &range) {
                          for (std::size_t c = range.begin(); c != range.end(); ++c)
                            f(c);
                        });
    }

    template <int dim>
    Eigen::Matrix<double, dim, dim + 1> gather(const Eigen::VectorXd                    &v,
                                               const std::array<unsigned int, dim + 1> &cell)
    {
      Eigen::Matrix<double, dim, dim + 1> m;
      for (int a = 0; a <= dim; ++a)
        m.col(a) = v.template segment<dim>(std::size_t(cell[a]) * dim);
      return m;
    }

  } // namespace cells

  template <int dim>
  struct TransferOperator<dim>::OldField
  {
    Eigen::Matrix<double, dim, dim, Eigen::DontAlign> K;
    Eigen::Matrix<double, dim, 1, Eigen::DontAlign>   k;
  };

  template <int dim>
  struct TransferOperator<dim>::CellTerms
  {
    double          value = 0;
    cells::CellVector<dim> grad_u, grad_x;
    cells::CellMatrix<dim> hess_u, mixed;
  };

} // namespace ritr::transfer
