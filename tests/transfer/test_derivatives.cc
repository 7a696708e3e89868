// Derivatives of b(x, y, u) = x^T (A_t(u) (x) I) y against central finite differences and
// against forward-mode AD (SecondOrderDual) of an independently written per-cell template,
// on jittered meshes, on meshes whose candidate cells overlap old cells in slivers, and on
// meshes where quadrature points leave the old domain (nearest-cell extension).
//
// Finite-difference step: 1e-6 times the mesh spacing. The analytic derivatives are those of
// the integrand with every quadrature point's old cell held fixed; a +-step moves a point by
// at most ~1e-6 h, so it changes old cell only if it lies that close to an old face. The
// helper fd_in_u detects that (comparing located_cells()) and skips the component; the tests
// assert that skips are rare.
#include "transfer_test_support.h"

#include <ritr/common/second_order_dual.h>
#include <ritr/common/small_matrix.h>
#include <ritr/transfer/transfer_operator.h>
#include <ritr/transfer/triangle_overlap.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

using namespace ritr;
using namespace ritr::transfer;
using namespace ritr::transfer::test;

namespace
{
  constexpr double fd_tolerance = 1e-6;

  template <int dim>
  void check_finite_differences(const Scenario<dim> &s, const SimplexQuadrature<dim> &rule,
                                const int min_distinct_old_cells, const bool expect_outside)
  {
    ASSERT_GT(min_measure(s.mesh, s.u_old), 0);
    ASSERT_GT(min_measure(s.mesh, s.u), 0);
    TransferOperator<dim> op(s.mesh.cells, rule);
    op.set_old_mesh(s.u_old);
    op.set_candidate(s.u);
    const std::size_t n_q = rule.size();

    // The geometry really is what the scenario claims.
    std::size_t most_distinct = 0;
    for (std::size_t c = 0; c < s.mesh.cells.size(); ++c)
      {
        const std::set<int> distinct(op.located_cells().begin() + c * n_q,
                                     op.located_cells().begin() + (c + 1) * n_q);
        most_distinct = std::max(most_distinct, distinct.size());
      }
    EXPECT_GE(most_distinct, std::size_t(min_distinct_old_cells));
    if (expect_outside)
      EXPECT_GT(op.n_outside(), 0u);

    const Eigen::Index    n = s.u.size();
    const Eigen::VectorXd x = random_field(n, 51) + s.u;
    const Eigen::VectorXd y = random_field(n, 52) + s.u_old;
    const double          step = 1e-6 * s.mesh.spacing();

    // db/du against differences of b.
    const Eigen::VectorXd g  = op.gradient_u(x, y);
    const auto            fg = fd_in_u(op, s.u, step, [&](const Eigen::VectorXd &v) {
      op.set_candidate(v);
      return Eigen::VectorXd::Constant(1, op.value(x, y));
    });
    EXPECT_GT(g.norm(), 1e-3);
    EXPECT_LE(fg.n_skipped, n / 10);
    EXPECT_LT(relative_error_where_defined(g.transpose(), fg.jacobian), fd_tolerance);

    // d2b/du2 against differences of the analytic gradient.
    const Eigen::MatrixXd H  = Eigen::MatrixXd(op.hessian_u(x, y));
    const auto            fH = fd_in_u(op, s.u, step, [&](const Eigen::VectorXd &v) {
      op.set_candidate(v);
      return op.gradient_u(x, y);
    });
    EXPECT_GT(H.norm(), 1e-3);
    EXPECT_LE(fH.n_skipped, n / 10);
    EXPECT_LT(relative_error_where_defined(H, fH.jacobian), fd_tolerance);
    EXPECT_LT(relative_error(H, H.transpose()), 1e-14);

    // d2b/dx du: column j = d(db/dx)/du_j, by differences in u of gradient_x ...
    const Eigen::MatrixXd Hxu  = Eigen::MatrixXd(op.hessian_xu(x, y));
    const auto            fHxu = fd_in_u(op, s.u, step, [&](const Eigen::VectorXd &v) {
      op.set_candidate(v);
      return op.gradient_x(y);
    });
    EXPECT_GT(Hxu.norm(), 1e-3);
    EXPECT_LE(fHxu.n_skipped, n / 10);
    EXPECT_LT(relative_error_where_defined(Hxu, fHxu.jacobian), fd_tolerance);
    // ... and row i = d(db/du)/dx_i, by differences in x (b is linear in x: no relocation).
    Eigen::MatrixXd fHux(n, n);
    Eigen::VectorXd xp = x;
    for (Eigen::Index i = 0; i < n; ++i)
      {
        xp[i]                     = x[i] + 1e-3;
        const Eigen::VectorXd gp  = op.gradient_u(xp, y);
        xp[i]                     = x[i] - 1e-3;
        const Eigen::VectorXd gm  = op.gradient_u(xp, y);
        xp[i]                     = x[i];
        fHux.row(i)               = (gp - gm).transpose() / 2e-3;
      }
    EXPECT_LT(relative_error(Hxu, fHux), 1e-9);
    std::printf("  dim %d, %zu cells, %u points outside, up to %zu old cells per candidate cell: "
                "relative FD errors du %.1e, du2 %.1e, dxdu %.1e; skipped columns %d, %d, %d of %ld\n",
                dim, s.mesh.cells.size(), op.n_outside(), most_distinct,
                relative_error_where_defined(g.transpose(), fg.jacobian),
                relative_error_where_defined(H, fH.jacobian), relative_error_where_defined(Hxu, fHxu.jacobian),
                fg.n_skipped, fH.n_skipped, fHxu.n_skipped, long(n));

    // db/dx is (A (x) I) y, and b = x^T db/dx.
    const Eigen::VectorXd      gx = op.gradient_x(y);
    const Eigen::MatrixXd      A  = Eigen::MatrixXd(op.transfer_matrix());
    Eigen::VectorXd            Ay(n);
    for (int k = 0; k < dim; ++k)
      {
        Eigen::VectorXd yk(n / dim);
        for (Eigen::Index i = 0; i < n / dim; ++i)
          yk[i] = y[i * dim + k];
        const Eigen::VectorXd r = A * yk;
        for (Eigen::Index i = 0; i < n / dim; ++i)
          Ay[i * dim + k] = r[i];
      }
    EXPECT_LT(relative_error(gx, Ay), 1e-13);
    EXPECT_NEAR(op.value(x, y), x.dot(gx), 1e-13 * std::abs(op.value(x, y)));
  }

  // Exact integration on the overlap polygons: A_t is C1 in u wherever the candidate stays
  // in the old domain, so every component of the derivatives is checked (no frozen
  // assignment, nothing skipped) except moves of nodes on a box face normal to it, which
  // r-ITR never makes: a part of a cell pushed outside the old domain takes its own start
  // cell's field, and there the one-sided derivatives may differ. Where candidate nodes or edges lie on old ones
  // (`ties`), the second derivatives jump: the Hessian is then the limit of the one on the
  // old mesh shifted by -delta d (triangle_overlap.h), checked against that mesh's.
  void check_exact_finite_differences(const Scenario<2> &s, const bool ties = false)
  {
    ASSERT_GT(min_measure(s.mesh, s.u), 0);
    TransferOperator<2> op(s.mesh.cells, degree_two_rule<2>(), TransferIntegration::exact);
    op.set_old_mesh(s.u_old);
    const Eigen::Index    n = s.u.size();
    const Eigen::VectorXd x = random_field(n, 71) + s.u;
    const Eigen::VectorXd y = random_field(n, 72) + s.u_old;
    const double          step = 1e-6 * s.mesh.spacing();
    op.set_candidate(s.u);
    const Eigen::VectorXd g   = op.gradient_u(x, y);
    const Eigen::MatrixXd H   = Eigen::MatrixXd(op.hessian_u(x, y));
    const Eigen::MatrixXd Hxu = Eigen::MatrixXd(op.hessian_xu(x, y));
    Eigen::MatrixXd       fg(1, n), fH(n, n), fHxu(n, n);
    Eigen::VectorXd       v      = s.u;
    int                   n_kept = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      {
        const bool normal_move = on_boundary(s.mesh.nodes[j]) && s.u[j] == s.u_old[j];
        if (normal_move)
          {
            fg.col(j).setConstant(std::nan(""));
            fH.col(j).setConstant(std::nan(""));
            fHxu.col(j).setConstant(std::nan(""));
            continue;
          }
        ++n_kept;
        std::array<double, 2>          values;
        std::array<Eigen::VectorXd, 2> gradients, state_gradients;
        for (int side = 0; side < 2; ++side)
          {
            v[j] = s.u[j] + (side == 0 ? step : -step);
            op.set_candidate(v);
            values[side]          = op.value(x, y);
            gradients[side]       = op.gradient_u(x, y);
            state_gradients[side] = op.gradient_x(y);
          }
        v[j]         = s.u[j];
        fg(0, j)     = (values[0] - values[1]) / (2 * step);
        fH.col(j)    = (gradients[0] - gradients[1]) / (2 * step);
        fHxu.col(j)  = (state_gradients[0] - state_gradients[1]) / (2 * step);
      }
    op.set_candidate(s.u);
    EXPECT_GE(n_kept, n / 2);
    EXPECT_GT(g.norm(), 1e-3);
    EXPECT_GT(H.norm(), 1e-3);
    EXPECT_GT(Hxu.norm(), 1e-3);
    const double eg = relative_error_where_defined(g.transpose(), fg);
    const double eH = relative_error_where_defined(H, fH), eHxu = relative_error_where_defined(Hxu, fHxu);
    EXPECT_LT(eg, fd_tolerance);
    if (!ties)
      EXPECT_LT(eH, fd_tolerance);
    EXPECT_LT(eHxu, fd_tolerance);
    // b = x . (A (x) I) y: the value and the matrix paths agree.
    const Eigen::MatrixXd A = Eigen::MatrixXd(op.transfer_matrix());
    double                xAy = 0;
    for (int k = 0; k < 2; ++k)
      for (Eigen::Index i = 0; i < n / 2; ++i)
        for (Eigen::Index j = 0; j < n / 2; ++j)
          xAy += x[i * 2 + k] * A(i, j) * y[j * 2 + k];
    EXPECT_NEAR(op.value(x, y), xAy, 1e-13 * std::abs(xAy));
    // The following Hessian, assembled from the same cell terms as the blocks, is
    // d2b/du2 + d2b/dxdu + d2b/dudx.
    std::vector<Eigen::Triplet<double>> following;
    op.add_hessian_following(x, y, 1.0, false, following);
    Eigen::SparseMatrix<double> F(n, n);
    F.setFromTriplets(following.begin(), following.end());
    EXPECT_LT(relative_error(Eigen::MatrixXd(F), H + Hxu + Hxu.transpose()), 1e-13);
    std::printf("  exact integration, %zu cells, %d of %ld components: relative FD errors du %.1e, du2 %.1e, "
                "dxdu %.1e\n", s.mesh.cells.size(), n_kept, long(n), eg, eH, eHxu);
  }

  // The scenario with its old mesh shifted by -delta d: no ties left.
  Scenario<2> shifted_old_mesh(Scenario<2> s, const double delta)
  {
    for (Eigen::Index i = 0; i < s.u_old.size(); ++i)
      s.u_old[i] -= delta * symbolic_shift[i % 2];
    return s;
  }

  void check_exact_at_ties(const Scenario<2> &s)
  {
    // Shifted by a thousandth of a cell, the mesh has no ties and slivers far wider than the
    // finite-difference step: every derivative is checked there.
    check_exact_finite_differences(shifted_old_mesh(s, 1e-3 * s.mesh.spacing()));
    const Eigen::Index    n = s.u.size();
    const Eigen::VectorXd x = random_field(n, 71) + s.u, y = random_field(n, 72) + s.u_old;
    const auto hessian = [&](const Scenario<2> &t) {
      TransferOperator<2> op(t.mesh.cells, degree_two_rule<2>(), TransferIntegration::exact);
      op.set_old_mesh(t.u_old);
      op.set_candidate(t.u);
      return Eigen::MatrixXd(op.hessian_u(x, y));
    };
    // The Hessian at the ties is the limit of the shifted meshes' as the shift vanishes.
    const Eigen::MatrixXd at_ties = hessian(s);
    const double far  = relative_error(at_ties, hessian(shifted_old_mesh(s, 1e-3 * s.mesh.spacing())));
    // (Much closer than 1e-5 h the shifted meshes' own slivers lose digits to round-off.)
    const double near = relative_error(at_ties, hessian(shifted_old_mesh(s, 1e-5 * s.mesh.spacing())));
    std::printf("  Hessian at the ties against the shifted old meshes': relative difference %.1e (shift 1e-3 h), "
                "%.1e (1e-5 h)\n", far, near);
    EXPECT_LT(near, 2e-4);
    EXPECT_LT(near, far / 20);
    // The first derivatives are continuous: checked at the ties themselves.
    check_exact_finite_differences(s, true);
  }

  // Along a straight path of the candidate mesh the quadrature transfer's value has kinks
  // (its slope jumps where a point changes old cell); the exact one's slope is continuous.
  // Measured by the largest jump of the first difference between neighbouring samples,
  // relative to the typical one.
  double largest_slope_jump(TransferOperator<2> &op, const Scenario<2> &s, const Eigen::VectorXd &x,
                            const Eigen::VectorXd &y, const Eigen::VectorXd &direction)
  {
    constexpr int       samples = 400;
    std::vector<double> values;
    for (int i = 0; i <= samples; ++i)
      {
        op.set_candidate(s.u + (double(i) / samples) * direction);
        values.push_back(op.value(x, y));
      }
    double jump = 0, slope = 0;
    for (int i = 1; i < samples; ++i)
      {
        jump  = std::max(jump, std::abs(values[i + 1] - 2 * values[i] + values[i - 1]));
        slope = std::max(slope, std::abs(values[i + 1] - values[i]));
      }
    return jump / slope;
  }

  // ---- Independent per-cell template for forward-mode AD ----
  // b_c(x_c, u_c) with the old cell of each quadrature point frozen; variables 0..n-1 are the
  // cell's x entries, n..2n-1 its u entries (node a, component k at a*dim + k).
  template <int dim>
  struct FrozenCell
  {
    std::array<unsigned int, dim + 1>                 cell;
    std::vector<double>                               weights;
    std::vector<std::array<double, dim + 1>>          lambdas;
    std::vector<Eigen::Matrix<double, dim + 1, dim>>  G; // barycentric gradients
    std::vector<Eigen::Matrix<double, dim + 1, 1>>    g; // barycentric offsets
    std::vector<Eigen::Matrix<double, dim, dim + 1>>  y; // old nodal y, one column per node
  };

  template <int dim, typename Scalar>
  Scalar frozen_cell_b(const std::array<Scalar, 2 * dim * (dim + 1)> &v, const FrozenCell<dim> &f)
  {
    constexpr int n = dim * (dim + 1);
    std::array<std::array<Scalar, dim>, dim + 1> nodes;
    for (int a = 0; a <= dim; ++a)
      for (int k = 0; k < dim; ++k)
        nodes[a][k] = v[n + a * dim + k];
    const Scalar J = determinant<dim, Scalar>(edge_matrix<dim, Scalar>(nodes));
    Scalar       sum(0.0);
    for (std::size_t q = 0; q < f.weights.size(); ++q)
      {
        std::array<Scalar, dim> X, s;
        for (int k = 0; k < dim; ++k)
          {
            X[k] = Scalar(0.0);
            s[k] = Scalar(0.0);
            for (int a = 0; a <= dim; ++a)
              {
                X[k] = X[k] + f.lambdas[q][a] * nodes[a][k];
                s[k] = s[k] + f.lambdas[q][a] * v[a * dim + k];
              }
          }
        Scalar phi(0.0);
        for (int b = 0; b <= dim; ++b)
          {
            Scalar mu(f.g[q][b]);
            for (int k = 0; k < dim; ++k)
              mu = mu + f.G[q](b, k) * X[k];
            for (int l = 0; l < dim; ++l)
              phi = phi + mu * f.y[q](l, b) * s[l];
          }
        sum = sum + f.weights[q] * phi;
      }
    return J * sum;
  }

  template <int dim>
  void check_against_dual(const Scenario<dim> &s, const SimplexQuadrature<dim> &rule)
  {
    constexpr int n_local = dim * (dim + 1);
    constexpr int N       = 2 * n_local;
    using Dual            = SecondOrderDual<N>;

    TransferOperator<dim> op(s.mesh.cells, rule);
    op.set_old_mesh(s.u_old);
    op.set_candidate(s.u);
    const Eigen::Index    n = s.u.size();
    const Eigen::VectorXd x = random_field(n, 61);
    const Eigen::VectorXd y = random_field(n, 62);

    double          value = 0;
    Eigen::VectorXd gu = Eigen::VectorXd::Zero(n), gx = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd Huu = Eigen::MatrixXd::Zero(n, n), Hxu = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t c = 0; c < s.mesh.cells.size(); ++c)
      {
        FrozenCell<dim> f;
        f.cell = s.mesh.cells[c];
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const int   o = op.located_cells()[c * rule.size() + q];
            const auto &m = op.locator().affine_map(o);
            f.weights.push_back(rule.weights[q]);
            f.lambdas.push_back(rule.points[q]);
            f.G.push_back(m.gradient);
            f.g.push_back(m.offset);
            Eigen::Matrix<double, dim, dim + 1> Y;
            for (int b = 0; b <= dim; ++b)
              Y.col(b) = y.segment<dim>(op.locator().cell(o)[b] * dim);
            f.y.push_back(Y);
          }
        std::array<Dual, N> v;
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            {
              v[a * dim + k]           = Dual::variable(a * dim + k, x[f.cell[a] * dim + k]);
              v[n_local + a * dim + k] = Dual::variable(n_local + a * dim + k, s.u[f.cell[a] * dim + k]);
            }
        const Dual r = frozen_cell_b<dim, Dual>(v, f);
        value += r.value;
        auto global = [&](const int i) { return f.cell[(i % n_local) / dim] * dim + i % dim; };
        for (int i = 0; i < n_local; ++i)
          {
            gx[global(i)] += r.grad[i];
            gu[global(i)] += r.grad[n_local + i];
            for (int j = 0; j < n_local; ++j)
              {
                Huu(global(i), global(j)) += r.hess(n_local + i, n_local + j);
                Hxu(global(i), global(j)) += r.hess(i, n_local + j);
              }
          }
      }
    EXPECT_NEAR(op.value(x, y), value, 1e-13 * std::abs(value));
    EXPECT_LT(relative_error(op.gradient_x(y), gx), 1e-12);
    EXPECT_LT(relative_error(op.gradient_u(x, y), gu), 1e-12);
    EXPECT_LT(relative_error(Eigen::MatrixXd(op.hessian_u(x, y)), Huu), 1e-12);
    EXPECT_LT(relative_error(Eigen::MatrixXd(op.hessian_xu(x, y)), Hxu), 1e-12);
  }

  template <int dim>
  SimplexQuadrature<dim> test_rule()
  {
    return composite_rule(degree_two_rule<dim>(), 2);
  }

} // namespace

TEST(TransferDerivatives, Jittered1D) { check_finite_differences(jittered_scenario<1>(6), test_rule<1>(), 2, false); }
TEST(TransferDerivatives, Jittered2D) { check_finite_differences(jittered_scenario<2>(3), test_rule<2>(), 2, false); }
TEST(TransferDerivatives, Jittered3D) { check_finite_differences(jittered_scenario<3>(3), test_rule<3>(), 2, false); }

TEST(TransferDerivatives, Slivers1D) { check_finite_differences(sliver_scenario<1>(6), composite_rule(degree_two_rule<1>(), 4), 3, false); }
TEST(TransferDerivatives, Slivers2D) { check_finite_differences(sliver_scenario<2>(4), composite_rule(degree_two_rule<2>(), 4), 3, false); }
TEST(TransferDerivatives, Slivers3D) { check_finite_differences(sliver_scenario<3>(3), composite_rule(degree_two_rule<3>(), 3), 3, false); }

TEST(TransferDerivatives, OutsideOldDomain2D) { check_finite_differences(outside_scenario<2>(3), test_rule<2>(), 2, true); }
TEST(TransferDerivatives, OutsideOldDomain3D) { check_finite_differences(outside_scenario<3>(2), test_rule<3>(), 2, true); }

TEST(TransferDerivatives, MatchesSecondOrderDual1D) { check_against_dual(sliver_scenario<1>(6), test_rule<1>()); }
TEST(TransferDerivatives, MatchesSecondOrderDual2D) { check_against_dual(sliver_scenario<2>(4), test_rule<2>()); }
TEST(TransferDerivatives, MatchesSecondOrderDual3D) { check_against_dual(sliver_scenario<3>(2), degree_two_rule<3>()); }

// Both keep the candidate's boundary nodes on the old ones: ties along the boundary.
TEST(TransferDerivatives, ExactIntegrationJittered2D) { check_exact_at_ties(jittered_scenario<2>(3)); }
TEST(TransferDerivatives, ExactIntegrationSlivers2D) { check_exact_at_ties(sliver_scenario<2>(4)); }
TEST(TransferDerivatives, ExactIntegrationOutsideOldDomain2D) { check_exact_finite_differences(outside_scenario<2>(3)); }
TEST(TransferDerivatives, ExactIntegrationSliding2D)
{
  // Boundary nodes slide along the box faces, onto old boundary edges: ties along the boundary.
  Scenario<2> s;
  s.mesh  = box_mesh<2>(4);
  s.u_old = jitter(s.mesh, s.mesh.nodes, 0.15, 91);
  s.u     = jitter(s.mesh, s.u_old, 0.2, 92);
  check_exact_at_ties(s);
}
TEST(TransferDerivatives, ExactIntegrationOnTheOldMesh2D)
{
  // Every candidate cell on its old cell and every edge on an old edge: the configuration
  // each r-ITR step starts from, decided by the symbolic shift.
  Scenario<2> s = jittered_scenario<2>(4);
  s.u           = s.u_old;
  check_exact_at_ties(s);
}

TEST(TransferDerivatives, ExactIntegrationHasNoKinks)
{
  const Scenario<2>     s = jittered_scenario<2>(4);
  const Eigen::Index    n = s.u.size();
  const Eigen::VectorXd x = random_field(n, 81) + s.u, y = random_field(n, 82) + s.u_old;
  // Interior nodes move by up to 0.1 spacing: many quadrature points cross old edges.
  const Eigen::VectorXd direction = jitter(s.mesh, s.u, 0.1, 83, true) - s.u;
  TransferOperator<2> quadrature(s.mesh.cells, test_rule<2>());
  TransferOperator<2> exact(s.mesh.cells, test_rule<2>(), TransferIntegration::exact);
  quadrature.set_old_mesh(s.u_old);
  exact.set_old_mesh(s.u_old);
  const double kinked = largest_slope_jump(quadrature, s, x, y, direction);
  const double smooth = largest_slope_jump(exact, s, x, y, direction);
  std::printf("  largest second difference / largest first difference along the path: quadrature %.1e, exact %.1e\n",
              kinked, smooth);
  EXPECT_LT(smooth, 0.01);
  EXPECT_GT(kinked, 10 * smooth);
}

TEST(TransferDerivatives, ExactIntegrationOnlyForTriangles)
{
  const BoxMesh<3> mesh = box_mesh<3>(2);
  EXPECT_THROW(TransferOperator<3>(mesh.cells, test_rule<3>(), TransferIntegration::exact), std::invalid_argument);
}

TEST(TransferDerivatives, ScaledAndProjectedHessian)
{
  const auto            s = sliver_scenario<2>(4);
  TransferOperator<2>   op(s.mesh.cells, test_rule<2>());
  op.set_old_mesh(s.u_old);
  op.set_candidate(s.u);
  const Eigen::VectorXd x = random_field(s.u.size(), 71), y = random_field(s.u.size(), 72);
  const Eigen::MatrixXd H = Eigen::MatrixXd(op.hessian_u(x, y));

  std::vector<Eigen::Triplet<double>> triplets(3, Eigen::Triplet<double>(0, 0, 1.0)); // appended to
  op.add_hessian_u(x, y, -2.5, false, triplets);
  Eigen::SparseMatrix<double> scaled(s.u.size(), s.u.size());
  scaled.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::MatrixXd expected = -2.5 * H;
  expected(0, 0) += 3.0;
  EXPECT_LT(relative_error(Eigen::MatrixXd(scaled), expected), 1e-14);

  // The unprojected Hessian is indefinite; projected blocks (after scaling) sum to PSD.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  EXPECT_LT(eig.eigenvalues().minCoeff(), -1e-6);
  for (const double scale : {1.0, -2.5})
    {
      triplets.clear();
      op.add_hessian_u(x, y, scale, true, triplets);
      Eigen::SparseMatrix<double> P(s.u.size(), s.u.size());
      P.setFromTriplets(triplets.begin(), triplets.end());
      const Eigen::MatrixXd Pd = Eigen::MatrixXd(P);
      EXPECT_LT(relative_error(Pd, Pd.transpose()), 1e-14);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_p(Pd);
      EXPECT_GT(eig_p.eigenvalues().minCoeff(), -1e-12 * Pd.norm());
    }
  EXPECT_LT(relative_error(Eigen::MatrixXd(op.hessian_u(x, y, true)),
                           [&] {
                             triplets.clear();
                             op.add_hessian_u(x, y, 1.0, true, triplets);
                             Eigen::SparseMatrix<double> P(s.u.size(), s.u.size());
                             P.setFromTriplets(triplets.begin(), triplets.end());
                             return Eigen::MatrixXd(P);
                           }()),
            1e-15);
}

TEST(TransferDerivatives, DeterministicAcrossRuns)
{
  // Parallel assembly with a fixed summation order: repeated evaluations are bitwise equal.
  const auto          s = sliver_scenario<3>(3);
  TransferOperator<3> op(s.mesh.cells, test_rule<3>());
  op.set_old_mesh(s.u_old);
  op.set_candidate(s.u);
  const Eigen::VectorXd x = random_field(s.u.size(), 81), y = random_field(s.u.size(), 82);
  const Eigen::MatrixXd A0 = Eigen::MatrixXd(op.transfer_matrix());
  const Eigen::MatrixXd H0 = Eigen::MatrixXd(op.hessian_u(x, y));
  const Eigen::VectorXd g0 = op.gradient_u(x, y);
  const double          b0 = op.value(x, y);
  const std::vector<int> located = op.located_cells();
  for (int run = 0; run < 3; ++run)
    {
      op.set_candidate(s.u);
      EXPECT_EQ(op.located_cells(), located);
      EXPECT_TRUE((Eigen::MatrixXd(op.transfer_matrix()).array() == A0.array()).all());
      EXPECT_TRUE((Eigen::MatrixXd(op.hessian_u(x, y)).array() == H0.array()).all());
      EXPECT_TRUE((op.gradient_u(x, y).array() == g0.array()).all());
      EXPECT_EQ(op.value(x, y), b0);
    }
}

TEST(TransferDerivatives, MisuseIsReported)
{
  const auto          s = jittered_scenario<2>(2);
  TransferOperator<2> op(s.mesh.cells, degree_two_rule<2>());
  EXPECT_THROW(op.set_candidate(s.u), std::logic_error);
  op.set_old_mesh(s.u_old);
  EXPECT_THROW(op.transfer_matrix(), std::logic_error);
  EXPECT_THROW(op.set_candidate(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  op.set_candidate(s.u);
  EXPECT_THROW(op.value(Eigen::VectorXd::Zero(3), s.u), std::invalid_argument);
  EXPECT_THROW(op.gradient_u(s.u, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  SimplexQuadrature<2> bad = degree_two_rule<2>();
  bad.weights[0]           = 1;
  EXPECT_THROW((TransferOperator<2>(s.mesh.cells, bad)), std::invalid_argument);
}
