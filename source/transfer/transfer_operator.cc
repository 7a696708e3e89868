#include <ritr/common/psd_projection.h>
#include <ritr/common/small_matrix.h>
#include <ritr/transfer/transfer_operator.h>

#include "transfer_cells.h"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ritr::transfer
{
  using namespace cells;

  namespace
  {
    constexpr int levi_civita(const int i, const int j) { return i == j ? 0 : (i < j ? 1 : -1); }
    constexpr int levi_civita(const int i, const int j, const int k)
    {
      return (i == j || j == k || i == k) ? 0 : ((j - i + 3) % 3 == 1 ? 1 : -1);
    }

    // det J of a cell with node columns U (J = [u_1 - u_0, ..., u_d - u_0]) and, optionally,
    // its gradient and Hessian with respect to the cell's node coordinates, entry a*dim + k
    // for component k of node a. det is a polynomial of degree dim in U.
    template <int dim>
    double determinant_derivatives(const Eigen::Matrix<double, dim, dim + 1> &U,
                                   CellVector<dim> *gradient, CellMatrix<dim> *hessian)
    {
      Eigen::Matrix<double, dim, dim> D;
      for (int j = 0; j < dim; ++j)
        D.col(j) = U.col(j + 1) - U.col(0);

      // Cofactors C_kj = d det / d D_kj.
      Eigen::Matrix<double, dim, dim> C;
      if constexpr (dim == 1)
        C(0, 0) = 1;
      else if constexpr (dim == 2)
        C << D(1, 1), -D(1, 0), -D(0, 1), D(0, 0);
      else
        {
          C.col(0) = D.col(1).cross(D.col(2));
          C.col(1) = D.col(2).cross(D.col(0));
          C.col(2) = D.col(0).cross(D.col(1));
        }
      const double det = (D.col(0).transpose() * C.col(0))(0, 0);

      // D's column j is u_{j+1} - u_0, so d/du_a = d/dD_{., a-1} for a >= 1 and
      // d/du_0 = -sum_j d/dD_{., j}.
      if (gradient)
        for (int k = 0; k < dim; ++k)
          {
            double sum = 0;
            for (int j = 0; j < dim; ++j)
              {
                (*gradient)[(j + 1) * dim + k] = C(k, j);
                sum += C(k, j);
              }
            (*gradient)[k] = -sum;
          }

      if (hessian)
        {
          hessian->setZero();
          if constexpr (dim > 1)
            {
              // d2 det / dD_ij dD_kl: 2D eps_ik eps_jl, 3D sum_mn eps_ikm eps_jln D_mn.
              Eigen::Matrix<double, dim * dim, dim * dim> HD;
              for (int i = 0; i < dim; ++i)
                for (int j = 0; j < dim; ++j)
                  for (int k = 0; k < dim; ++k)
                    for (int l = 0; l < dim; ++l)
                      {
                        double h = 0;
                        if constexpr (dim == 2)
                          h = levi_civita(i, k) * levi_civita(j, l);
                        else
                          for (int m = 0; m < 3; ++m)
                            for (int n = 0; n < 3; ++n)
                              h += levi_civita(i, k, m) * levi_civita(j, l, n) * D(m, n);
                        HD(i * dim + j, k * dim + l) = h;
                      }
              // Chain through D_{., j} = u_{j+1} - u_0: weight s(a, j) = [a == j+1] - [a == 0].
              auto s = [](const int a, const int j) { return (a == j + 1 ? 1.0 : 0.0) - (a == 0 ? 1.0 : 0.0); };
              for (int a = 0; a <= dim; ++a)
                for (int b = 0; b <= dim; ++b)
                  for (int j = 0; j < dim; ++j)
                    {
                      const double saj = s(a, j);
                      if (saj == 0)
                        continue;
                      for (int l = 0; l < dim; ++l)
                        {
                          const double sbl = s(b, l);
                          if (sbl == 0)
                            continue;
                          for (int i = 0; i < dim; ++i)
                            for (int k = 0; k < dim; ++k)
                              (*hessian)(a * dim + i, b * dim + k) += saj * sbl * HD(i * dim + j, k * dim + l);
                        }
                    }
            }
        }
      return det;
    }

  } // namespace


  template <int dim>
  TransferOperator<dim>::TransferOperator(std::vector<Cell> cells, SimplexQuadrature<dim> quadrature,
                                          const TransferIntegration integration)
    : cells_(std::move(cells)), quadrature_(std::move(quadrature)), integration_(integration)
  {
    check_rule(quadrature_);
    if (integration_ == TransferIntegration::exact && dim != 2)
      throw std::invalid_argument("exact transfer integration is implemented for triangles only");
  }

  template <int dim>
  void TransferOperator<dim>::set_old_mesh(const Eigen::VectorXd &u_old, const double tolerance)
  {
    if (u_old.size() % dim != 0)
      throw std::invalid_argument("TransferOperator: u_old size is not a multiple of dim");
    n_nodes_       = u_old.size() / dim;
    locator_       = OldMeshLocator<dim>(cells_, u_old, tolerance);
    has_old_mesh_  = true;
    has_candidate_ = false;
  }

  template <int dim>
  void TransferOperator<dim>::check_ready(const char *what) const
  {
    if (!has_old_mesh_ || !has_candidate_)
      throw std::logic_error(std::string("TransferOperator::") + what +
                             ": call set_old_mesh and set_candidate first");
  }

  template <int dim>
  void TransferOperator<dim>::check_field(const Eigen::VectorXd &v, const char *name) const
  {
    if (v.size() != Eigen::Index(n_nodes_) * dim)
      throw std::invalid_argument(std::string("TransferOperator: ") + name + " has size " +
                                  std::to_string(v.size()) + ", expected " +
                                  std::to_string(n_nodes_ * dim));
  }

  template <int dim>
  void TransferOperator<dim>::set_candidate(const Eigen::VectorXd &u)
  {
    if (!has_old_mesh_)
      throw std::logic_error("TransferOperator::set_candidate: call set_old_mesh first");
    check_field(u, "u");
    u_ = u;
    if (integration_ == TransferIntegration::exact)
      {
        find_overlaps();
        located_.clear();
        n_outside_     = 0;
        has_candidate_ = true;
        return;
      }
    const std::size_t n_q = quadrature_.size();
    located_.assign(cells_.size() * n_q, -1);
    std::vector<unsigned int> n_distinct(cells_.size()), n_out(cells_.size());
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      const auto U = gather<dim>(u_, cells_[c]);
      // Same connectivity: candidate cell c starts out on top of old cell c; afterwards the
      // previous point's cell is the best guess.
      int                         hint = static_cast<int>(c);
      int                        *loc  = &located_[c * n_q];
      unsigned int                out  = 0;
      Eigen::Matrix<double, dim + 1, 1> lambda;
      for (std::size_t q = 0; q < n_q; ++q)
        {
          for (int a = 0; a <= dim; ++a)
            lambda[a] = quadrature_.points[q][a];
          const Location<dim> found = locator_.locate(U * lambda, hint);
          loc[q]                    = found.cell;
          hint                      = found.cell;
          out += found.inside ? 0 : 1;
        }
      // Distinct old cells (the number of blocks this cell adds to A); usually a handful.
      std::vector<int> seen;
      for (std::size_t q = 0; q < n_q; ++q)
        if (std::find(seen.begin(), seen.end(), loc[q]) == seen.end())
          seen.push_back(loc[q]);
      n_distinct[c] = seen.size();
      n_out[c]      = out;
    });
    block_offsets_.assign(cells_.size() + 1, 0);
    n_outside_ = 0;
    for (std::size_t c = 0; c < cells_.size(); ++c)
      {
        block_offsets_[c + 1] = block_offsets_[c] + n_distinct[c];
        n_outside_ += n_out[c];
      }
    has_candidate_ = true;
  }

  template <int dim>
  typename TransferOperator<dim>::SparseMatrix TransferOperator<dim>::transfer_matrix() const
  {
    check_ready("transfer_matrix");
    if (integration_ == TransferIntegration::exact)
      return exact_transfer_matrix();
    constexpr int            block = (dim + 1) * (dim + 1);
    const std::size_t        n_q   = quadrature_.size();
    std::vector<Triplet>     triplets(block_offsets_.back() * block);
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      const auto   U = gather<dim>(u_, cells_[c]);
      const double J = determinant_derivatives<dim>(U, nullptr, nullptr);
      // One (d+1)x(d+1) block per distinct old cell, in order of first appearance so that
      // the triplet order (and hence the summation order) is fixed.
      const int                        *loc = &located_[c * n_q];
      std::vector<unsigned char>        done(n_q, 0);
      std::size_t                       out = block_offsets_[c] * block;
      Eigen::Matrix<double, dim + 1, 1> lambda;
      for (std::size_t q0 = 0; q0 < n_q; ++q0)
        {
          if (done[q0])
            continue;
          const int   o = loc[q0];
          const auto &m = locator_.affine_map(o);
          Eigen::Matrix<double, dim + 1, dim + 1> B = Eigen::Matrix<double, dim + 1, dim + 1>::Zero();
          for (std::size_t q = q0; q < n_q; ++q)
            {
              if (loc[q] != o)
                continue;
              done[q] = 1;
              for (int a = 0; a <= dim; ++a)
                lambda[a] = quadrature_.points[q][a];
              const Eigen::Matrix<double, dim + 1, 1> mu = m.gradient * (U * lambda) + m.offset;
              B += quadrature_.weights[q] * lambda * mu.transpose();
            }
          const Cell &old = locator_.cell(o);
          for (int a = 0; a <= dim; ++a)
            for (int b = 0; b <= dim; ++b)
              triplets[out++] = Triplet(cells_[c][a], old[b], J * B(a, b));
        }
    });
    SparseMatrix A(n_nodes_, n_nodes_);
    A.setFromTriplets(triplets.begin(), triplets.end());
    return A;
  }

  template <int dim>
  typename TransferOperator<dim>::SparseMatrix TransferOperator<dim>::mass_matrix() const
  {
    check_ready("mass_matrix");
    constexpr int        block = (dim + 1) * (dim + 1);
    std::vector<Triplet> triplets(cells_.size() * block);
    // int lambda_a lambda_b = |T| (1 + delta_ab) / ((d+1)(d+2)), |T| = det J / d!.
    const double scale = 1.0 / (factorial(dim) * (dim + 1) * (dim + 2));
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      const double J   = determinant_derivatives<dim>(gather<dim>(u_, cells_[c]), nullptr, nullptr);
      std::size_t  out = c * block;
      for (int a = 0; a <= dim; ++a)
        for (int b = 0; b <= dim; ++b)
          triplets[out++] = Triplet(cells_[c][a], cells_[c][b], J * scale * (a == b ? 2.0 : 1.0));
    });
    SparseMatrix M(n_nodes_, n_nodes_);
    M.setFromTriplets(triplets.begin(), triplets.end());
    return M;
  }

  template <int dim>
  std::vector<typename TransferOperator<dim>::OldField>
  TransferOperator<dim>::old_field(const Eigen::VectorXd &y) const
  {
    check_field(y, "y");
    std::vector<OldField> field(locator_.n_cells());
    for_each_cell(field.size(), [&](const std::size_t o) {
      const auto  Y = gather<dim>(y, locator_.cell(o));
      const auto &m = locator_.affine_map(o);
      field[o].K    = Y * m.gradient;
      field[o].k    = Y * m.offset;
    });
    return field;
  }

  template <int dim>
  template <bool value, bool grad_u, bool hess_u, bool grad_x, bool mixed>
  void TransferOperator<dim>::cell_terms(const unsigned int c, const Eigen::VectorXd *x,
                                         const std::vector<OldField> &field, CellTerms &terms) const
  {
    if (integration_ == TransferIntegration::exact)
      {
        if constexpr (hess_u || mixed)
          exact_cell_derivatives(c, *x, field, terms);
        else if constexpr (grad_u)
          exact_cell_gradient(c, *x, field, terms);
        else
          exact_cell_values(c, x, field, terms);
        return;
      }
    constexpr bool need_s  = value || grad_u || hess_u;
    constexpr bool need_dJ = grad_u || hess_u || mixed;

    const auto U = gather<dim>(u_, cells_[c]);
    Eigen::Matrix<double, dim, dim + 1> Xc;
    if constexpr (need_s)
      Xc = gather<dim>(*x, cells_[c]);
    CellVector<dim> dJ;
    const double    J = determinant_derivatives<dim>(U, need_dJ ? &dJ : nullptr,
                                                  hess_u ? &terms.hess_u : nullptr);

    // Phi = sum w phi;  V_(a,k) = sum w lambda_a (K^T s)_k;  P_(a,l) = sum w lambda_a Y_l;
    // Q_(a'l, ak) = sum w lambda_a' lambda_a K_lk.
    double          Phi = 0;
    CellVector<dim> V   = CellVector<dim>::Zero();
    CellVector<dim> P   = CellVector<dim>::Zero();
    if constexpr (mixed)
      terms.mixed.setZero();

    const std::size_t n_q = quadrature_.size();
    const int        *loc = &located_[std::size_t(c) * n_q];
    Eigen::Matrix<double, dim + 1, 1> lambda;
    for (std::size_t q = 0; q < n_q; ++q)
      {
        for (int a = 0; a <= dim; ++a)
          lambda[a] = quadrature_.points[q][a];
        const double    w = quadrature_.weights[q];
        const OldField &f = field[loc[q]];
        const Eigen::Matrix<double, dim, 1> Y = f.K * (U * lambda) + f.k;
        if constexpr (need_s)
          {
            const Eigen::Matrix<double, dim, 1> s = Xc * lambda;
            Phi += w * s.dot(Y);
            if constexpr (grad_u || hess_u)
              {
                const Eigen::Matrix<double, dim, 1> t = f.K.transpose() * s;
                for (int a = 0; a <= dim; ++a)
                  V.template segment<dim>(a * dim) += (w * lambda[a]) * t;
              }
          }
        if constexpr (grad_x || mixed)
          for (int a = 0; a <= dim; ++a)
            P.template segment<dim>(a * dim) += (w * lambda[a]) * Y;
        if constexpr (mixed)
          for (int a2 = 0; a2 <= dim; ++a2)
            for (int a = 0; a <= dim; ++a)
              terms.mixed.template block<dim, dim>(a2 * dim, a * dim) += (w * lambda[a2] * lambda[a]) * f.K;
      }

    if constexpr (value)
      terms.value = J * Phi;
    if constexpr (grad_u)
      terms.grad_u = Phi * dJ + J * V;
    if constexpr (hess_u)
      {
        // terms.hess_u holds d2J here.
        terms.hess_u *= Phi;
        terms.hess_u += dJ * V.transpose() + V * dJ.transpose();
      }
    if constexpr (grad_x)
      terms.grad_x = J * P;
    if constexpr (mixed)
      {
        terms.mixed *= J;
        terms.mixed += P * dJ.transpose();
      }
  }

  template <int dim>
  double TransferOperator<dim>::value(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const
  {
    check_ready("value");
    check_field(x, "x");
    const auto          field = old_field(y);
    std::vector<double> values(cells_.size());
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<true, false, false, false, false>(c, &x, field, terms);
      values[c] = terms.value;
    });
    double sum = 0; // serial: the same sum in every run
    for (const double v : values)
      sum += v;
    return sum;
  }

  template <int dim>
  Eigen::VectorXd TransferOperator<dim>::scatter_cell_vectors(const std::vector<double> &local) const
  {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n_nodes_ * dim);
    for (std::size_t c = 0; c < cells_.size(); ++c)
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          g[std::size_t(cells_[c][a]) * dim + k] += local[c * n_cell_dofs + a * dim + k];
    return g;
  }

  template <int dim>
  Eigen::VectorXd TransferOperator<dim>::gradient_x(const Eigen::VectorXd &y) const
  {
    check_ready("gradient_x");
    const auto          field = old_field(y);
    std::vector<double> local(cells_.size() * n_cell_dofs);
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<false, false, false, true, false>(c, nullptr, field, terms);
      std::copy(terms.grad_x.data(), terms.grad_x.data() + n_cell_dofs, &local[c * n_cell_dofs]);
    });
    return scatter_cell_vectors(local);
  }

  template <int dim>
  Eigen::VectorXd TransferOperator<dim>::gradient_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const
  {
    check_ready("gradient_u");
    check_field(x, "x");
    const auto          field = old_field(y);
    std::vector<double> local(cells_.size() * n_cell_dofs);
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<false, true, false, false, false>(c, &x, field, terms);
      std::copy(terms.grad_u.data(), terms.grad_u.data() + n_cell_dofs, &local[c * n_cell_dofs]);
    });
    return scatter_cell_vectors(local);
  }

  template <int dim>
  template <typename BlockOfCell>
  void TransferOperator<dim>::append_cell_blocks(std::vector<Triplet> &triplets, const BlockOfCell &block_of_cell) const
  {
    // Every cell fills its own slice, so the blocks are computed in parallel and the result
    // does not depend on thread scheduling.
    constexpr int     block = n_cell_dofs * n_cell_dofs;
    const std::size_t start = triplets.size();
    triplets.resize(start + cells_.size() * block);
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      const CellMatrix<dim> H   = block_of_cell(c);
      std::size_t           out = start + c * block;
      for (int i = 0; i < n_cell_dofs; ++i)
        for (int j = 0; j < n_cell_dofs; ++j)
          triplets[out++] = Triplet(cells_[c][i / dim] * dim + i % dim, cells_[c][j / dim] * dim + j % dim, H(i, j));
    });
  }

  template <int dim>
  void TransferOperator<dim>::add_hessian_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                                            const double scale, const bool project_psd,
                                            std::vector<Triplet> &triplets) const
  {
    check_ready("add_hessian_u");
    check_field(x, "x");
    const auto field = old_field(y);
    append_cell_blocks(triplets, [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<false, false, true, false, false>(c, &x, field, terms);
      CellMatrix<dim> H = scale * terms.hess_u;
      return project_psd ? CellMatrix<dim>(project_to_psd(H)) : H;
    });
  }

  template <int dim>
  void TransferOperator<dim>::add_reference_derivatives(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                                                        const double scale, const bool following, Eigen::VectorXd &gu,
                                                        std::vector<Triplet> &huu, std::vector<Triplet> *hxu) const
  {
    check_ready("add_reference_derivatives");
    check_field(x, "x");
    const auto             field = old_field(y);
    std::vector<CellTerms> terms(cells_.size());
    std::vector<double>    local(cells_.size() * n_cell_dofs);
    for_each_cell(cells_.size(), [&](const std::size_t c) {
      cell_terms<false, true, true, false, true>(c, &x, field, terms[c]);
      for (int i = 0; i < n_cell_dofs; ++i)
        local[c * n_cell_dofs + i] = scale * terms[c].grad_u[i];
    });
    gu += scatter_cell_vectors(local);
    append_cell_blocks(huu, [&](const std::size_t c) {
      const CellTerms &t = terms[c];
      CellMatrix<dim>  H = scale * t.hess_u;
      if (following)
        H += scale * (t.mixed + t.mixed.transpose());
      return H;
    });
    if (hxu)
      append_cell_blocks(*hxu, [&](const std::size_t c) { return CellMatrix<dim>(scale * terms[c].mixed); });
  }

  template <int dim>
  void TransferOperator<dim>::add_hessian_following(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                                                    const double scale, const bool project_psd,
                                                    std::vector<Triplet> &triplets) const
  {
    check_ready("add_hessian_following");
    check_field(x, "x");
    const auto field = old_field(y);
    append_cell_blocks(triplets, [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<false, false, true, false, true>(c, &x, field, terms);
      CellMatrix<dim> H = scale * (terms.hess_u + terms.mixed + terms.mixed.transpose());
      return project_psd ? CellMatrix<dim>(project_to_psd(H)) : H;
    });
  }

  template <int dim>
  typename TransferOperator<dim>::SparseMatrix
  TransferOperator<dim>::hessian_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                                   const bool project_psd) const
  {
    std::vector<Triplet> triplets;
    add_hessian_u(x, y, 1.0, project_psd, triplets);
    SparseMatrix H(n_nodes_ * dim, n_nodes_ * dim);
    H.setFromTriplets(triplets.begin(), triplets.end());
    return H;
  }

  template <int dim>
  void TransferOperator<dim>::add_hessian_xu(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                                             const double scale, std::vector<Triplet> &triplets) const
  {
    check_ready("add_hessian_xu");
    check_field(x, "x");
    const auto field = old_field(y);
    append_cell_blocks(triplets, [&](const std::size_t c) {
      CellTerms terms;
      cell_terms<false, false, false, false, true>(c, &x, field, terms);
      return CellMatrix<dim>(scale * terms.mixed);
    });
  }

  template <int dim>
  typename TransferOperator<dim>::SparseMatrix
  TransferOperator<dim>::hessian_xu(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const
  {
    std::vector<Triplet> triplets;
    add_hessian_xu(x, y, 1.0, triplets);
    SparseMatrix H(n_nodes_ * dim, n_nodes_ * dim);
    H.setFromTriplets(triplets.begin(), triplets.end());
    return H;
  }

  template <int dim>
  Eigen::VectorXd TransferOperator<dim>::project(const Eigen::VectorXd &y) const
  {
    check_ready("project");
    if (n_nodes_ == 0 || y.size() % n_nodes_ != 0)
      throw std::invalid_argument("TransferOperator::project: y size " + std::to_string(y.size()) +
                                  " is not a multiple of the node count");
    const Eigen::Index n_components = y.size() / n_nodes_;
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::Map<const RowMajor> Y(y.data(), n_nodes_, n_components);

    Eigen::SimplicialLDLT<SparseMatrix> solver(mass_matrix());
    if (solver.info() != Eigen::Success)
      throw std::runtime_error("TransferOperator::project: candidate mass matrix is singular "
                               "(degenerate cells or nodes in no cell)");
    // A vector field's (A (x) I) y is db/dx, computed cell by cell without assembling A.
    const Eigen::MatrixXd rhs = n_components == dim ? Eigen::MatrixXd(RowMajor(Eigen::Map<const RowMajor>(
                                                        gradient_x(y).data(), n_nodes_, n_components))) :
                                                      Eigen::MatrixXd(transfer_matrix() * Y);
    const RowMajor        Z   = solver.solve(rhs);
    return Eigen::Map<const Eigen::VectorXd>(Z.data(), Z.size());
  }

  template <int dim>
  Eigen::VectorXd TransferOperator<dim>::project(const Eigen::VectorXd &y, const Eigen::VectorXd &u)
  {
    set_candidate(u);
    return project(y);
  }

  template class TransferOperator<1>;
  template class TransferOperator<2>;
  template class TransferOperator<3>;
} // namespace ritr::transfer
