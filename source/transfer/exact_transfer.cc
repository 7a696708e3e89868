// TransferOperator with exact integration (triangles): each candidate cell clipped by the
// old cells it overlaps, the quadratic integrand integrated exactly on the overlap polygons
// (triangle_overlap.h), with dual numbers over the candidate's six coordinates for the
// derivatives in u. Why the reference cell and the symbolic shift: transfer_operator.h.
#include <ritr/common/first_order_dual.h>
#include <ritr/common/second_order_dual.h>
#include <ritr/transfer/transfer_operator.h>
#include <ritr/transfer/triangle_overlap.h>

#include "transfer_cells.h"

#include <algorithm>
#include <type_traits>

namespace ritr::transfer
{
  using namespace cells;

  namespace
  {
    // Candidate vertex coordinate (node a, component k) as independent variable a*2 + k of
    // the dual numbers, or as a plain value.
    template <typename S>
    S coordinate(const int a, const int k, const double value)
    {
      if constexpr (std::is_same_v<S, double>)
        return value;
      else
        return S::variable(a * 2 + k, value);
    }

    template <typename S>
    std::array<Point2<S>, 3> candidate_triangle(const Eigen::Matrix<double, 2, 3> &U)
    {
      std::array<Point2<S>, 3> K;
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 2; ++k)
          K[a][k] = coordinate<S>(a, k, U(k, a));
      return K;
    }

    // P_ak = int_K lambda_a Y_k with Y the old field: Y_c (the field of candidate c's own start
    // cell, extended linearly) on all of K, plus Y_o - Y_c on K's overlap with every other old
    // cell o.
    template <typename S, typename Field, typename Locator>
    std::array<std::array<S, 2>, 3> field_moments(const unsigned int c, const std::array<Point2<S>, 3> &K,
                                                  const TriangleBarycentric<S> &lambda, const Field &field,
                                                  const std::vector<int> &overlaps, const Locator &locator)
    {
      const auto rows = [](const auto &f) {
        return std::array<std::array<double, 3>, 2>{{{f.K(0, 0), f.K(0, 1), f.k[0]}, {f.K(1, 0), f.K(1, 1), f.k[1]}}};
      };
      std::array<std::array<S, 2>, 3> P{};
      const auto                      own = rows(field[c]);
      add_triangle_moments<S, 2>(K, lambda, own, P);
      for (const int o : overlaps)
        {
          if (o == int(c))
            continue;
          auto F = rows(field[o]);
          for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 3; ++j)
              F[k][j] -= own[k][j];
          add_overlap_moments<S, 2>(K, lambda, locator.affine_map(o), F, P);
        }
      return P;
    }
  } // namespace

  template <int dim>
  void TransferOperator<dim>::find_overlaps()
  {
    overlaps_.assign(cells_.size(), {});
    if constexpr (dim == 2)
      for_each_cell(cells_.size(), [&](const std::size_t c) {
        const auto U = gather<dim>(u_, cells_[c]);
        const auto K = candidate_triangle<double>(U);
        Aabb<dim>  box;
        box.min = U.rowwise().minCoeff();
        box.max = U.rowwise().maxCoeff();
        box.inflate(1e-9 * (box.max - box.min).norm());
        locator_.for_each_cell_near(box, [&](const int o) {
          // Only the cells the clipping finds (in plain arithmetic: cheap next to the duals).
          if (clip(K, locator_.affine_map(o)).size >= 3)
            overlaps_[c].push_back(o);
        });
        std::sort(overlaps_[c].begin(), overlaps_[c].end());  // a fixed summation order
      });
  }

  template <int dim>
  typename TransferOperator<dim>::SparseMatrix TransferOperator<dim>::exact_transfer_matrix() const
  {
    std::vector<std::vector<Triplet>> per_cell(cells_.size());
    if constexpr (dim == 2)
      for_each_cell(cells_.size(), [&](const std::size_t c) {
        // As in field_moments: the old shape functions of cell c on all of K, and on each
        // overlap with another old cell o its shape functions minus cell c's.
        const auto                        K = candidate_triangle<double>(gather<dim>(u_, cells_[c]));
        const TriangleBarycentric<double> lambda(K);
        const auto rows = [&](const int o) {
          const AffineBarycentric<2>          &mu = locator_.affine_map(o);
          std::array<std::array<double, 3>, 3> F;
          for (int b = 0; b < 3; ++b)
            F[b] = {mu.gradient(b, 0), mu.gradient(b, 1), mu.offset[b]};
          return F;
        };
        const auto &own_cell = locator_.cell(c);
        const auto  own      = rows(c);
        std::array<std::array<double, 3>, 3> B{};
        add_triangle_moments<double, 3>(K, lambda, own, B);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            per_cell[c].emplace_back(cells_[c][a], own_cell[b], B[a][b]);
        for (const int o : overlaps_[c])
          {
            if (o == int(c))
              continue;
            const auto                           other = rows(o);
            std::array<std::array<double, 3>, 6> F;
            for (int b = 0; b < 3; ++b)
              F[b] = other[b], F[3 + b] = own[b];
            std::array<std::array<double, 6>, 3> m{};
            add_overlap_moments<double, 6>(K, lambda, locator_.affine_map(o), F, m);
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b)
                {
                  per_cell[c].emplace_back(cells_[c][a], locator_.cell(o)[b], m[a][b]);
                  per_cell[c].emplace_back(cells_[c][a], own_cell[b], -m[a][3 + b]);
                }
          }
      });
    std::vector<Triplet> triplets;
    for (const auto &t : per_cell)
      triplets.insert(triplets.end(), t.begin(), t.end());
    SparseMatrix A(n_nodes_, n_nodes_);
    A.setFromTriplets(triplets.begin(), triplets.end());
    return A;
  }

  template <int dim>
  void TransferOperator<dim>::exact_cell_values(const unsigned int c, const Eigen::VectorXd *x,
                                                const std::vector<OldField> &field, CellTerms &terms) const
  {
    if constexpr (dim == 2)
      {
        const auto                        K = candidate_triangle<double>(gather<dim>(u_, cells_[c]));
        const TriangleBarycentric<double> lambda(K);
        const auto                        P = field_moments<double>(c, K, lambda, field, overlaps_[c], locator_);
        Eigen::Matrix<double, 2, 3> Xc = Eigen::Matrix<double, 2, 3>::Zero();
        if (x)
          Xc = gather<dim>(*x, cells_[c]);
        terms.value = 0;
        for (int a = 0; a < 3; ++a)
          for (int k = 0; k < 2; ++k)
            {
              terms.value += Xc(k, a) * P[a][k];
              terms.grad_x[a * 2 + k] = P[a][k];
            }
      }
    else
      (void)c, (void)x, (void)field, (void)terms;
  }

  namespace
  {
    // The cell terms of candidate cell c (candidate triangle U) from dual numbers of type S over
    // its six coordinates: value, grad_x and grad_u, and with second-order duals also hess_u and
    // the mixed block.
    template <typename S, typename Field, typename Locator, typename Terms>
    void dual_cell_terms(const unsigned int c, const Eigen::Matrix<double, 2, 3> &U, const Eigen::Matrix<double, 2, 3> &Xc,
                         const Field &field, const std::vector<int> &overlaps, const Locator &locator, Terms &terms)
    {
      constexpr bool               second = std::is_same_v<S, SecondOrderDual<6>>;
      const auto                   K      = candidate_triangle<S>(U);
      const TriangleBarycentric<S> lambda(K);
      const auto                   P = field_moments<S>(c, K, lambda, field, overlaps, locator);
      terms.value                    = 0;
      terms.grad_u.setZero();
      if constexpr (second)
        terms.hess_u.setZero();
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 2; ++k)
          {
            const S &p = P[a][k];
            terms.value += Xc(k, a) * p.value;
            terms.grad_x[a * 2 + k] = p.value;
            terms.grad_u += Xc(k, a) * p.grad;
            if constexpr (second)
              {
                terms.hess_u += Xc(k, a) * p.hess;
                terms.mixed.row(a * 2 + k) = p.grad.transpose();
              }
          }
    }
  } // namespace

  template <int dim>
  void TransferOperator<dim>::exact_cell_derivatives(const unsigned int c, const Eigen::VectorXd &x,
                                                     const std::vector<OldField> &field, CellTerms &terms) const
  {
    if constexpr (dim == 2)
      dual_cell_terms<SecondOrderDual<6>>(c, gather<dim>(u_, cells_[c]), gather<dim>(x, cells_[c]), field, overlaps_[c],
                                          locator_, terms);
    else
      (void)c, (void)x, (void)field, (void)terms;
  }

  template <int dim>
  void TransferOperator<dim>::exact_cell_gradient(const unsigned int c, const Eigen::VectorXd &x,
                                                  const std::vector<OldField> &field, CellTerms &terms) const
  {
    if constexpr (dim == 2)
      dual_cell_terms<FirstOrderDual<6>>(c, gather<dim>(u_, cells_[c]), gather<dim>(x, cells_[c]), field, overlaps_[c],
                                         locator_, terms);
    else
      (void)c, (void)x, (void)field, (void)terms;
  }

#define RITR_INSTANTIATE(dim)                                                                                          \
  template void TransferOperator<dim>::find_overlaps();                                                                \
  template typename TransferOperator<dim>::SparseMatrix TransferOperator<dim>::exact_transfer_matrix() const;          \
  template void TransferOperator<dim>::exact_cell_values(unsigned int, const Eigen::VectorXd *,                        \
                                                         const std::vector<OldField> &, CellTerms &) const;            \
  template void TransferOperator<dim>::exact_cell_derivatives(unsigned int, const Eigen::VectorXd &,                   \
                                                              const std::vector<OldField> &, CellTerms &) const;   \
  template void TransferOperator<dim>::exact_cell_gradient(unsigned int, const Eigen::VectorXd &,                      \
                                                           const std::vector<OldField> &, CellTerms &) const;
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::transfer
