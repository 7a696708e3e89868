// The pieces of the trust-region outer step: Steihaug's truncated CG against dense linear
// algebra (interior Newton step, boundary steps, negative curvature), and the matrix-free
// reduced Hessian against the dense Schur complement it stands for, and the folding of
// prescribed entries that follow u (sliding Dirichlet nodes) against finite differences of
// the composition; and the outer model's step against the measure barrier it keeps exact;
// and the sparse Cholesky factorization and the shifted sparse inverse that preconditions CG,
// which these rest on.
#include <ritr/adaptivity/outer_model.h>
#include <ritr/adaptivity/reduced_hessian.h>
#include <ritr/solver/shifted_sparse_inverse.h>
#include <ritr/solver/steihaug_cg.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "finite_difference.h"

using namespace ritr;

namespace
{
  Eigen::MatrixXd random_symmetric(const int n, const double diagonal_shift, const unsigned seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::MatrixXd                        a(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        a(i, j) = u(rng);
    return 0.5 * (a + a.transpose()) + diagonal_shift * Eigen::MatrixXd::Identity(n, n);
  }

  Eigen::VectorXd random_vector(const int n, const unsigned seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd                        v(n);
    for (int i = 0; i < n; ++i)
      v[i] = u(rng);
    return v;
  }

  // Every entry of a dense matrix, as the terms assemble blocks.
  Triplets triplets(const Eigen::MatrixXd &m)
  {
    Triplets t;
    for (int i = 0; i < m.rows(); ++i)
      for (int j = 0; j < m.cols(); ++j)
        t.emplace_back(i, j, m(i, j));
    return t;
  }

  double model(const Eigen::MatrixXd &S, const Eigen::VectorXd &g, const Eigen::VectorXd &p)
  {
    return g.dot(p) + 0.5 * p.dot(S * p);
  }
} // namespace

TEST(SteihaugCG, InsideALargeRegionItIsTheNewtonStep)
{
  const Eigen::MatrixXd S = random_symmetric(12, 8.0, 1);  // positive definite
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff(), 0);
  const Eigen::VectorXd g = random_vector(12, 2);
  const auto r = steihaug_cg([&](const Eigen::VectorXd &p) { return Eigen::VectorXd(S * p); }, g, 1e6, 1e-12 * g.norm(), 100);
  const Eigen::VectorXd newton = -S.ldlt().solve(g);
  EXPECT_TRUE(r.interior);
  EXPECT_FALSE(r.negative_curvature);
  EXPECT_LT((r.step - newton).norm(), 1e-10 * newton.norm());
  EXPECT_NEAR(r.predicted_change, model(S, g, r.step), 1e-12 * std::abs(r.predicted_change));
}

TEST(SteihaugCG, ALooseToleranceStopsEarlyBelowTheCauchyPoint)
{
  // Adaptivity/model tolerance: CG stops inside a large region once |S p + g| <= eta |g|, in
  // fewer products than the tight solve, and its step still lowers the model at least as much
  // as the Cauchy point (CG's first iterate; later ones only lower it further).
  const Eigen::MatrixXd S = random_symmetric(40, 2.0, 7) + 30 * Eigen::VectorXd::LinSpaced(40, 0, 1).asDiagonal().toDenseMatrix();
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff(), 0);
  const Eigen::VectorXd g     = random_vector(40, 8);
  const auto            apply = [&](const Eigen::VectorXd &p) { return Eigen::VectorXd(S * p); };
  const auto            tight = steihaug_cg(apply, g, 1e6, 1e-2 * g.norm(), 100);
  const auto            loose = steihaug_cg(apply, g, 1e6, 0.2 * g.norm(), 100);
  EXPECT_TRUE(loose.interior);
  EXPECT_LE((S * loose.step + g).norm(), 0.2 * g.norm());
  EXPECT_GT((S * loose.step + g).norm(), 1e-2 * g.norm());  // it did stop early
  EXPECT_LT(loose.iterations, tight.iterations);
  const Eigen::VectorXd cauchy = -(g.squaredNorm() / g.dot(S * g)) * g;
  EXPECT_LE(model(S, g, loose.step), model(S, g, cauchy));
  EXPECT_LE(model(S, g, tight.step), model(S, g, loose.step));
  EXPECT_NEAR(loose.predicted_change, model(S, g, loose.step), 1e-12 * std::abs(loose.predicted_change));
}

TEST(SteihaugCG, ASmallRegionEndsOnItsBoundaryBelowTheCauchyPoint)
{
  const Eigen::MatrixXd S = random_symmetric(12, 8.0, 3);
  const Eigen::VectorXd g = random_vector(12, 4);
  const double radius = 0.1 * S.ldlt().solve(g).norm();
  const auto r = steihaug_cg([&](const Eigen::VectorXd &p) { return Eigen::VectorXd(S * p); }, g, radius, 1e-12, 100);
  EXPECT_FALSE(r.interior);
  EXPECT_NEAR(r.step.norm(), radius, 1e-12 * radius);
  // The Cauchy point: the model's minimum along -g within the region.
  const double          gSg    = g.dot(S * g);
  const double          tau    = std::min(g.squaredNorm() / gSg, radius / g.norm());
  const Eigen::VectorXd cauchy = -tau * g;
  EXPECT_LE(model(S, g, r.step), model(S, g, cauchy) + 1e-14);
  EXPECT_NEAR(r.predicted_change, model(S, g, r.step), 1e-12 * std::abs(r.predicted_change));
}

TEST(SteihaugCG, NegativeCurvatureIsFollowedToTheBoundary)
{
  const Eigen::MatrixXd S = random_symmetric(12, -0.5, 5);
  ASSERT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff(), 0);
  const Eigen::VectorXd g = random_vector(12, 6);
  const double radius = 3.0;
  const auto r = steihaug_cg([&](const Eigen::VectorXd &p) { return Eigen::VectorXd(S * p); }, g, radius, 1e-12, 100);
  EXPECT_FALSE(r.interior);
  EXPECT_NEAR(r.step.norm(), radius, 1e-12 * radius);
  EXPECT_LT(r.predicted_change, 0);
  EXPECT_NEAR(r.predicted_change, model(S, g, r.step), 1e-12 * std::abs(r.predicted_change));
}

TEST(SteihaugCG, APreconditionedRegionIsMeasuredInItsMetric)
{
  // M enters through M^-1 only; the step's M-norm comes from CG's recurrences.
  const Eigen::MatrixXd M = random_symmetric(12, 6.0, 9);
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0);
  const auto            m_inverse = M.ldlt();
  const auto            precondition = [&](const Eigen::VectorXd &v) { return Eigen::VectorXd(m_inverse.solve(v)); };
  const auto            metric_norm  = [&](const Eigen::VectorXd &p) { return std::sqrt(p.dot(M * p)); };
  for (const double curvature_shift : {8.0, -0.5})  // definite: boundary or Newton step; indefinite: boundary
    {
      const Eigen::MatrixXd S     = random_symmetric(12, curvature_shift, 10);
      const Eigen::VectorXd g     = random_vector(12, 11);
      const auto            apply = [&](const Eigen::VectorXd &p) { return Eigen::VectorXd(S * p); };
      const auto bounded = steihaug_cg(apply, g, 0.05, 1e-12 * g.norm(), 100, precondition);
      EXPECT_FALSE(bounded.interior);
      EXPECT_NEAR(metric_norm(bounded.step), 0.05, 1e-10);
      EXPECT_NEAR(bounded.metric_norm, 0.05, 1e-12);
      EXPECT_NEAR(bounded.predicted_change, model(S, g, bounded.step), 1e-10 * std::abs(bounded.predicted_change));
      const auto free = steihaug_cg(apply, g, 1e6, 1e-12 * g.norm(), 100, precondition);
      if (curvature_shift > 0)
        {
          EXPECT_TRUE(free.interior);
          EXPECT_LT((free.step + S.ldlt().solve(g)).norm(), 1e-9 * free.step.norm());
        }
      EXPECT_NEAR(free.metric_norm, metric_norm(free.step), 1e-9 * metric_norm(free.step));
    }
}

TEST(SparseCholesky, SolvesAndRegularisesReproducibly)
{
  // Definite: exact solves, one symbolic analysis for two matrices of one pattern, and many
  // right-hand sides at once. Semi-definite (a zero row): a shift, the same from a second
  // factorization object. (A matrix this small gets CHOLMOD's simplicial factorization.)
  const Eigen::MatrixXd definite = random_symmetric(9, 10.0, 3);
  Eigen::MatrixXd       semi     = definite;
  semi.row(4).setZero();
  semi.col(4).setZero();
  const Eigen::VectorXd b = random_vector(9, 4);
  const Eigen::MatrixXd B = definite.leftCols(3);
  std::optional<double> first_shift;
  for (int attempt = 0; attempt < 2; ++attempt)
    {
      SparseCholesky                    cholesky;
      const Eigen::SparseMatrix<double> lower = Eigen::MatrixXd(definite.triangularView<Eigen::Lower>()).sparseView();
      EXPECT_EQ(cholesky.factorize(lower), 0.0);
      EXPECT_LT((definite * cholesky.solve(b) - b).norm(), 1e-12 * b.norm());
      EXPECT_LT((definite * cholesky.solve_columns(B) - B).norm(), 1e-12 * B.norm());
      const Eigen::SparseMatrix<double> doubled = 2 * lower;
      EXPECT_EQ(cholesky.factorize(doubled), 0.0);
      EXPECT_LT((2 * definite * cholesky.solve(b) - b).norm(), 1e-12 * b.norm());
      EXPECT_EQ(cholesky.n_symbolic_analyses(), 1u);
      Eigen::SparseMatrix<double> semi_lower = Eigen::MatrixXd(semi.triangularView<Eigen::Lower>()).sparseView();
      semi_lower.makeCompressed();
      const double shift = cholesky.factorize(semi_lower);
      EXPECT_GT(shift, 0.0);
      if (first_shift)
        {
          EXPECT_EQ(shift, *first_shift);
        }
      first_shift = shift;
      // Indefinite (a negative diagonal entry): shifted too, not factorized as LDL'.
      Eigen::MatrixXd indefinite = definite;
      indefinite(2, 2)           = -indefinite(2, 2);
      Eigen::SparseMatrix<double> indefinite_lower =
        Eigen::MatrixXd(indefinite.triangularView<Eigen::Lower>()).sparseView();
      indefinite_lower.makeCompressed();
      EXPECT_GT(cholesky.factorize(indefinite_lower), 0.0);
    }
}

// CG's preconditioner: sigma I plus a sparse B on a few unknowns, against the dense inverse.
TEST(ShiftedSparseInverse, InvertsTheShiftedMatrix)
{
  const int                   n = 9;
  Eigen::MatrixXd             dense_B = Eigen::MatrixXd::Zero(n, n);
  const std::vector<int>      cell{2, 5, 7};
  for (const int a : cell)
    for (const int b : cell)
      dense_B(a, b) = (a == b ? 3.0 : 0.0) + 0.5;  // positive definite on the cell
  Eigen::SparseMatrix<double> B = dense_B.sparseView();
  ShiftedSparseInverse        inverse;
  for (const double sigma : {1e-3, 2.0})
    {
      inverse.factorize(sigma, B);
      EXPECT_EQ(inverse.touched(), cell);
      const Eigen::MatrixXd M = sigma * Eigen::MatrixXd::Identity(n, n) + dense_B;
      const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
      EXPECT_LT((inverse.solve(v) - M.ldlt().solve(v)).norm(), 1e-12 * M.ldlt().solve(v).norm());
    }
  inverse.factorize(0.5, Eigen::SparseMatrix<double>(n, n));  // nothing touched: v / sigma
  EXPECT_TRUE(inverse.touched().empty());
  EXPECT_LT((inverse.solve(Eigen::VectorXd::Ones(n)) - 2.0 * Eigen::VectorXd::Ones(n)).norm(), 1e-15);
}

TEST(ReducedHessian, MatchesTheDenseSchurComplement)
{
  // State of 10 entries, 2 of them prescribed; reference of 8 entries moving in a basis of 5.
  const int       n_z = 10, n_u = 8, n_b = 5;
  const std::vector<int> free_state{0, 1, 2, 4, 5, 6, 8, 9};
  const Eigen::MatrixXd hxx = random_symmetric(n_z, 12.0, 7);  // positive definite
  const Eigen::MatrixXd huu = random_symmetric(n_u, 0.0, 8);
  Eigen::MatrixXd       hxu(n_z, n_u);
  for (int j = 0; j < n_u; ++j)
    hxu.col(j) = random_vector(n_z, 20 + j);
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(n_u, n_b);  // sliding-like: unit and tangent columns
  basis(0, 0) = 1, basis(1, 1) = 1, basis(2, 2) = 0.6, basis(3, 2) = 0.8, basis(5, 3) = 1, basis(7, 4) = 1;

  SparseCholesky cholesky;
  const Eigen::SparseMatrix<double> sparse_basis = basis.sparseView();
  const ReducedHessian S(triplets(huu), triplets(hxx), triplets(hxu), n_z, free_state, sparse_basis, cholesky);
  EXPECT_EQ(S.state_shift(), 0.0);
  EXPECT_TRUE(S.dense());
  SparseCholesky       cholesky_free;  // the matrix-free path, a back-substitution per product
  const ReducedHessian S_free(triplets(huu), triplets(hxx), triplets(hxu), n_z, free_state, sparse_basis,
                              cholesky_free, 0);
  EXPECT_FALSE(S_free.dense());

  const int       n_f = free_state.size();
  Eigen::MatrixXd hxx_f(n_f, n_f), hxu_f(n_f, n_u);
  for (int a = 0; a < n_f; ++a)
    {
      hxu_f.row(a) = hxu.row(free_state[a]);
      for (int b = 0; b < n_f; ++b)
        hxx_f(a, b) = hxx(free_state[a], free_state[b]);
    }
  const Eigen::MatrixXd dense = basis.transpose() * (huu - hxu_f.transpose() * hxx_f.ldlt().solve(hxu_f)) * basis;
  for (unsigned seed = 40; seed < 43; ++seed)
    {
      const Eigen::VectorXd p = random_vector(n_b, seed);
      EXPECT_LT((S.apply(p) - dense * p).norm(), 1e-12 * (dense * p).norm());
      EXPECT_LT((S_free.apply(p) - dense * p).norm(), 1e-12 * (dense * p).norm());
      // The response of the state: -H_xx^-1 H_xu B p on the free entries, 0 on prescribed ones.
      const Eigen::VectorXd response = -hxx_f.ldlt().solve(hxu_f * (basis * p));
      const Eigen::VectorXd dz       = S.state_response(p);
      EXPECT_EQ(dz[3], 0.0);
      EXPECT_EQ(dz[7], 0.0);
      for (int a = 0; a < n_f; ++a)
        EXPECT_NEAR(dz[free_state[a]], response[a], 1e-12 * response.norm());
    }
}

TEST(ReducedHessian, FoldedFollowingEntriesAreTheComposition)
{
  // R(z, u) quadratic (plus a cubic in z so that g_z varies); the body's 6 state entries
  // share numbering with u, 2 obstacle entries follow; entries 1 and 4 are prescribed and
  // follow u (z_p = u_p + c_p), entry 7 is prescribed and fixed.
  const int              n_u = 6, n_z = 8;
  const std::vector<int> following{1, 4}, free_state{0, 2, 3, 5, 6};
  const Eigen::MatrixXd  H = random_symmetric(n_z + n_u, 0.0, 11);
  const Eigen::VectorXd  b = random_vector(n_z + n_u, 12), c = random_vector(n_z, 13);
  const auto R = [&](const Eigen::VectorXd &z, const Eigen::VectorXd &u) {
    Eigen::VectorXd w(n_z + n_u);
    w << z, u;
    return 0.5 * w.dot(H * w) + b.dot(w) + 0.1 * z.array().cube().sum();
  };
  // The composition in (free state y, u).
  const auto compose = [&](const Eigen::VectorXd &y, const Eigen::VectorXd &u) {
    Eigen::VectorXd z = c;
    for (std::size_t a = 0; a < free_state.size(); ++a)
      z[free_state[a]] = y[a];
    for (const int p : following)
      z[p] = u[p] + c[p];
    return z;
  };
  const Eigen::VectorXd y = random_vector(free_state.size(), 14), u = random_vector(n_u, 15);
  const Eigen::VectorXd z = compose(y, u);

  // The blocks as the terms assemble them, at (z, u).
  Eigen::VectorXd w(n_z + n_u);
  w << z, u;
  Eigen::VectorXd gradient = H * w + b;
  gradient.head(n_z) += 0.3 * z.array().square().matrix();
  Eigen::MatrixXd hzz = H.topLeftCorner(n_z, n_z);
  hzz.diagonal() += 0.6 * z;
  Eigen::VectorXd gu = gradient.tail(n_u);
  const Eigen::VectorXd gx = gradient.head(n_z);
  Triplets huu = triplets(H.bottomRightCorner(n_u, n_u)), hxu = triplets(H.topRightCorner(n_z, n_u));
  fold_following_prescribed(following, gx, triplets(hzz), gu, huu, hxu);

  const auto R_u = [&](const Eigen::VectorXd &v) { return R(compose(y, v), v); };
  EXPECT_LT(test_support::relative_error(gu, test_support::fd_gradient(R_u, u, 1e-6)), 1e-8);
  const auto dR_du = [&](const Eigen::VectorXd &v) {
    return Eigen::VectorXd(test_support::fd_gradient([&](const Eigen::VectorXd &s) { return R(compose(y, s), s); }, v, 1e-5));
  };
  EXPECT_LT(test_support::relative_error(test_support::dense(huu, n_u, n_u), test_support::fd_jacobian(dR_du, u, 1e-4)),
            1e-6);
  // The coupling's free rows: d/du of dR/dy.
  const auto dR_dy = [&](const Eigen::VectorXd &v) {
    return Eigen::VectorXd(test_support::fd_gradient([&](const Eigen::VectorXd &s) { return R(compose(s, v), v); }, y, 1e-5));
  };
  const Eigen::MatrixXd coupling = test_support::dense(hxu, n_z, n_u);
  Eigen::MatrixXd       free_rows(free_state.size(), n_u);
  for (std::size_t a = 0; a < free_state.size(); ++a)
    free_rows.row(a) = coupling.row(free_state[a]);
  EXPECT_LT(test_support::relative_error(free_rows, test_support::fd_jacobian(dR_dy, u, 1e-4)), 1e-6);
}

namespace
{
  // One reference triangle (0,0), (1,0), (0,1) whose third node a spring pulls to (0.8, 0.15):
  // the pull would shrink the cell to 0.075, below the measure barrier's threshold 0.2, so
  // the model's minimum has the node slide to x = 0.8 while the barrier holds its height.
  SimplexMesh<2> unit_triangle()
  {
    SimplexMesh<2> mesh;
    mesh.reference.resize(6);
    mesh.reference << 0, 0, 1, 0, 0, 1;
    mesh.cells = {{{0, 1, 2}}};
    return mesh;
  }

  // The outer model at the unmoved triangle. There is no state: S is the spring's Hessian
  // (the barrier's is 0 there, outside its threshold).
  struct CollapsingTriangle
  {
    const double                 w_hat = 0.2, kappa = 1.0, spring = 1.0;
    const SimplexMesh<2>         mesh  = unit_triangle();
    Eigen::SparseMatrix<double>  basis;
    Eigen::VectorXd              u = mesh.reference, target = u, g;
    const std::vector<int>       free_state{0};
    SparseCholesky               state_cholesky;
    MeasureBarrierModel<2>       barrier{mesh, basis, w_hat, kappa};
    std::optional<ReducedHessian> S;
    std::optional<OuterModel<2>>  model;

    CollapsingTriangle()
    {
      basis.resize(6, 6);
      basis.setIdentity();
      target.tail(2) << 0.8, 0.15;
      g = spring * (u - target);
      barrier.set_point(u);
      Triplets huu;
      for (int i = 0; i < 6; ++i)
        huu.emplace_back(i, i, spring);
      S.emplace(huu, Triplets{{0, 0, 1.0}}, Triplets{}, 1, free_state, basis, state_cholesky);
      model.emplace(*S, g, basis);
    }
    // The spring and the barrier at v, computed directly.
    double objective(const Eigen::VectorXd &v) const
    {
      return 0.5 * spring * (v - target).squaredNorm() + reference_measure_barrier(mesh, v, w_hat, kappa);
    }
    OuterModel<2>::Step propose(const double radius)
    {
      const auto no_filter = [](const Eigen::VectorXd &, const Eigen::VectorXd &) { return 1.0; };
      return model->propose(radius, 1e-4, 1e-12, no_filter, barrier);
    }
  };
} // namespace

TEST(OuterModel, TheStepSlidesAlongTheMeasureBarrierToTheModelsMinimum)
{
  CollapsingTriangle t;
  ASSERT_EQ(t.barrier.at_point().value, 0.0);  // the cell starts outside the barrier
  const auto step = t.propose(10.0);

  const Eigen::VectorXd end = t.u + step.du;
  // The prediction is the model's actual change, and the model is R here.
  EXPECT_NEAR(step.predicted, t.objective(end) - t.objective(t.u), 1e-12);
  // A minimum of R: its gradient by finite differences vanishes to the forcing term.
  const auto R = [&](const Eigen::VectorXd &v) { return t.objective(v); };
  EXPECT_LT(test_support::fd_gradient(R, end, 1e-7).norm(), 1e-3 * t.g.norm());
  EXPECT_NEAR(end[4], 0.8, 5e-3);  // slid along the barrier (a cut of the straight pull stops short)
  const double w = 0.5 * end[5];   // the cell's measure: half the node's height
  EXPECT_GT(w, 0.075);             // held above where the spring alone would take it
  EXPECT_LT(w, t.w_hat);           // inside the barrier, where it balances the spring
}

TEST(OuterModel, AStepStaysInsideItsRegion)
{
  CollapsingTriangle t;
  for (const double radius : {0.05, 0.3, 0.6})
    {
      const auto step = t.propose(radius);
      EXPECT_LE(t.model->length(step.p), radius * (1 + 1e-9));
      EXPECT_LT(step.predicted, 0.0);
      EXPECT_NEAR(step.predicted, t.objective(t.u + step.du) - t.objective(t.u), 1e-12);
    }
}
