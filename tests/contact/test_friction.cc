// Lagged IPC friction: mollifier functions, normal force, tangent bases, invariances,
// gradient and Hessian against finite differences in both mollifier regimes, PSD Hessian,
// 1D (no friction).
#include <ritr/contact/barrier.h>
#include <ritr/contact/friction.h>

#include "contact_test_support.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

using ritr::log_barrier_derivative;
using namespace ritr::contact;
using namespace ritr::contact::test_support;

const std::mt19937::result_type ritr::contact::test_support::rng_seed = 31;

namespace
{
  template <int dim>
  std::vector<double> tangential_norms(const std::vector<FrictionConstraint<dim>> &fr,
                                       const Eigen::MatrixXd &V, const Eigen::MatrixXd &V0)
  {
    std::vector<double> y;
    for (const auto &fc : fr)
      {
        Vec<dim> r = Vec<dim>::Zero();
        for (int i = 0; i < fc.n_vertices; ++i)
          r += fc.coefficients[i] * (V.row(fc.vertices[i]) - V0.row(fc.vertices[i])).transpose();
        y.push_back((fc.basis.transpose() * r).norm());
      }
    return y;
  }

  // Largest Coulomb force bound mu lambda over the friction constraints (0 if none).
  template <int dim>
  double max_friction_force(const std::vector<FrictionConstraint<dim>> &fr)
  {
    double lambda_max = 0;
    for (const auto &fc : fr)
      lambda_max = std::max(lambda_max, fc.mu * fc.normal_force);
    return lambda_max;
  }

  // hessian_scale: natural size of the Hessian (it vanishes identically for 2D sliding,
  // where f0(|u|) = |u| is linear on each side, so ||H|| alone is no reference there).
  template <int dim>
  void expect_friction_derivatives_match_fd(const std::vector<FrictionConstraint<dim>> &fr,
                                            const Eigen::MatrixXd &V, const Eigen::MatrixXd &V0,
                                            const double eps, const double hessian_scale)
  {
    expect_assembled_derivatives_match_fd(
      [&](const Eigen::MatrixXd &W) { return friction_energy<dim>(fr, W, V0, eps); },
      [&](const Eigen::MatrixXd &W) { return friction_gradient<dim>(fr, W, V0, eps); },
      [&](const Eigen::MatrixXd &W) { return friction_hessian<dim>(fr, W, V0, eps, false); }, V,
      1e-5, hessian_scale);
  }

  // Both regimes: all |u| well below eps_v h, and all well above.
  template <int dim>
  void check_friction_scene(const CollisionSurface<dim> &s, const Eigen::MatrixXd &V_lag,
                            const double dhat)
  {
    const auto cs = build_constraints<dim>(s, V_lag, V_lag, dhat);
    const auto w  = random_weights(s.n_vertices, static_cast<int>(s.edges.size()));
    const auto fr = build_friction_constraints<dim>(cs, V_lag, dhat, 10.0, w, 0.4);
    ASSERT_GT(fr.size(), 2u);

    Eigen::MatrixXd dV = Eigen::MatrixXd::Zero(V_lag.rows(), dim);
    for (int i = 0; i < dV.size(); ++i)
      dV(i) = uniform();

    // Sticking regime: eps three times the largest |u|.
    {
      const Eigen::MatrixXd V   = V_lag + 0.01 * dV;
      const auto            ys  = tangential_norms<dim>(fr, V, V_lag);
      const double          eps = 3.0 * *std::max_element(ys.begin(), ys.end());
      expect_friction_derivatives_match_fd<dim>(fr, V, V_lag, eps, max_friction_force(fr) / eps);
    }
    // Sliding regime: eps a hundredth of the smallest |u|.
    {
      const Eigen::MatrixXd V   = V_lag + 0.1 * dV;
      const auto            ys  = tangential_norms<dim>(fr, V, V_lag);
      const double          y_min = *std::min_element(ys.begin(), ys.end());
      const double          eps = 0.01 * y_min;
      ASSERT_GT(eps, 0.0);
      expect_friction_derivatives_match_fd<dim>(fr, V, V_lag, eps, max_friction_force(fr) / y_min);
    }
  }
} // namespace

TEST(FrictionMollifier, DerivativesAreConsistent)
{
  const double eps = 0.2;
  for (const double y : {1e-3, 0.05, 0.1, 0.19, 0.25, 1.0})
    {
      const double h = 1e-7;
      EXPECT_NEAR(friction_f1(y, eps),
                  (friction_f0(y + h, eps) - friction_f0(y - h, eps)) / (2 * h), 1e-7);
      EXPECT_NEAR(friction_f1_over_y(y, eps), friction_f1(y, eps) / y, 1e-12);
      const double df1 = (friction_f1(y + h, eps) - friction_f1(y - h, eps)) / (2 * h);
      EXPECT_NEAR(friction_f2_term(y, eps), (df1 * y - friction_f1(y, eps)) / (y * y * y),
                  1e-6 * std::abs(friction_f2_term(y, eps)));
    }
  // C1 at eps, f0(0) = eps/3, f1(0) = 0, f1/y finite at 0.
  EXPECT_NEAR(friction_f0(eps * (1 - 1e-12), eps), eps, 1e-12);
  EXPECT_NEAR(friction_f1(eps * (1 - 1e-12), eps), 1.0, 1e-11);
  EXPECT_NEAR(friction_f0(0.0, eps), eps / 3, 1e-15);
  EXPECT_EQ(friction_f1(0.0, eps), 0.0);
  EXPECT_NEAR(friction_f1_over_y(0.0, eps), 2 / eps, 1e-12);
  EXPECT_EQ(friction_f2_term(0.0, eps), 0.0);
}

TEST(Friction, OneDimensionalHasNoFriction)
{
  CollisionSurface<1> s;
  s.n_vertices = 2;
  Eigen::MatrixXd V(2, 1);
  V << 0.0, 0.01;
  const auto cs = build_constraints<1>(s, V, V, 0.1);
  ASSERT_EQ(cs.size(), 1u);
  const auto fr = build_friction_constraints<1>(cs, V, 0.1, 1.0, {}, 0.5);
  EXPECT_TRUE(fr.empty());
  Eigen::MatrixXd V1(2, 1);
  V1 << 0.3, -0.2;
  EXPECT_EQ(friction_energy<1>(fr, V1, V, 1e-3), 0.0);
  EXPECT_EQ(friction_gradient<1>(fr, V1, V, 1e-3).norm(), 0.0);
  EXPECT_TRUE(friction_hessian<1>(fr, V1, V, 1e-3).empty());
}

TEST(Friction, NormalForceBasisAndCoefficients2D)
{
  // Point 0.05 above the edge from (-1, 0) to (1, 0), closest point at alpha = 0.6.
  CollisionSurface<2> s;
  s.n_vertices = 3;
  s.edges      = {{{1, 2}}};
  Eigen::MatrixXd V(3, 2);
  V << 0.2, 0.05, -1, 0, 1, 0;
  const double dhat = 0.1, kappa = 7.0, mu = 0.3;
  const auto   cs   = build_constraints<2>(s, V, V, dhat);
  ASSERT_EQ(cs.size(), 1u);
  ConstraintWeights w;
  w.vertex_weights = {0.25, 1.0, 1.0};
  const auto fr    = build_friction_constraints<2>(cs, V, dhat, kappa, w, mu);
  ASSERT_EQ(fr.size(), 1u);
  const auto  &fc = fr[0];
  const double d  = 0.05 * 0.05;
  EXPECT_NEAR(fc.normal_force,
              -kappa * 0.25 * log_barrier_derivative(d, dhat * dhat) * 2 * std::sqrt(d), 1e-12);
  EXPECT_GT(fc.normal_force, 0.0);
  EXPECT_EQ(fc.mu, mu);
  EXPECT_EQ(fc.n_vertices, 3);
  EXPECT_NEAR(fc.coefficients[0], 1.0, 1e-15);
  EXPECT_NEAR(fc.coefficients[1], -0.4, 1e-15);
  EXPECT_NEAR(fc.coefficients[2], -0.6, 1e-15);
  EXPECT_NEAR(std::abs(fc.basis(0, 0)), 1.0, 1e-15);
  EXPECT_NEAR(fc.basis(1, 0), 0.0, 1e-15);

  // Sliding the point by 0.1 along the edge with eps = 1e-3: the force on the point is
  // mu lambda along the motion (Coulomb), the edge gets the reaction split 0.4 / 0.6.
  Eigen::MatrixXd V1 = V;
  V1(0, 0) += 0.1;
  const Eigen::VectorXd g = friction_gradient<2>(fr, V1, V, 1e-3);
  EXPECT_NEAR(g[0], mu * fc.normal_force, 1e-12);
  EXPECT_NEAR(g[1], 0.0, 1e-15);
  EXPECT_NEAR(g[2], -0.4 * mu * fc.normal_force, 1e-12);
  EXPECT_NEAR(g[4], -0.6 * mu * fc.normal_force, 1e-12);
  EXPECT_NEAR(friction_energy<2>(fr, V1, V, 1e-3), mu * fc.normal_force * 0.1, 1e-14);

  // Moving along the normal produces no tangential displacement.
  Eigen::MatrixXd V2 = V;
  V2(0, 1) -= 0.02;
  EXPECT_NEAR(friction_energy<2>(fr, V2, V, 1e-3), mu * fc.normal_force * 1e-3 / 3, 1e-15);
  EXPECT_NEAR(friction_gradient<2>(fr, V2, V, 1e-3).norm(), 0.0, 1e-15);
}

TEST(Friction, TangentBasesAreOrthonormalAndOrthogonalToNormal3D)
{
  // A hand-made scene with every distance type (obstacle triangle; body points above its
  // interior, beside an edge, beside a corner; a body edge crossing over a triangle edge),
  // then random scenes.
  Scene<3> made;
  made.add_vertex(Vec<3>(0, 0, 0), true);
  made.add_vertex(Vec<3>(1, 0, 0), true);
  made.add_vertex(Vec<3>(0, 1, 0), true);
  made.surface.faces = {{{0, 1, 2}}};
  made.add_vertex(Vec<3>(0.2, 0.2, 0.1), false);
  made.add_vertex(Vec<3>(0.5, -0.1, 0.05), false);
  made.add_vertex(Vec<3>(-0.1, -0.1, 0.05), false);
  const int e0 = made.add_vertex(Vec<3>(0.55, -0.5, 0.1), false);
  const int e1 = made.add_vertex(Vec<3>(0.45, 0.5, 0.1), false);
  made.surface.edges = edges_of_faces(made.surface.faces);
  made.surface.edges.push_back({{e0, e1}});

  int n_types[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 4; ++trial)
    {
      auto       s  = trial == 0 ? made : scene_3d();
      const auto V  = s.V();
      const auto cs = build_constraints<3>(s.surface, V, V, trial == 0 ? 0.2 : 0.35);
      for (const auto &c : cs)
        {
          const auto fr =
            build_friction_constraints<3>({c}, V, trial == 0 ? 0.2 : 0.35, 1.0, {}, 0.5);
          if (fr.empty())
            continue; // e.g. exactly parallel edges: no force
          const auto &fc = fr[0];
          ++n_types[static_cast<int>(c.distance_type)];
          EXPECT_LE((fc.basis.transpose() * fc.basis - Eigen::Matrix2d::Identity()).norm(), 1e-12);
          // Coefficients sum to zero (rigid translations do not slide) and give the closest
          // point difference, which is the contact normal.
          Vec<3> r   = Vec<3>::Zero();
          double sum = 0;
          for (int i = 0; i < fc.n_vertices; ++i)
            {
              r += fc.coefficients[i] * V.row(fc.vertices[i]).transpose();
              sum += fc.coefficients[i];
            }
          EXPECT_NEAR(sum, 0.0, 1e-14);
          EXPECT_NEAR(r.squaredNorm(), c.distance_sqr, 1e-12);
          EXPECT_LE((fc.basis.transpose() * r).norm(), 1e-10 * r.norm());
        }
    }
  for (int t = 0; t < 4; ++t)
    EXPECT_GT(n_types[t], 0) << "distance type " << t << " not exercised";
}

TEST(Friction, RigidTranslationDoesNotSlide)
{
  auto            s  = scene_2d();
  const auto      V  = s.V();
  const auto      cs = build_constraints<2>(s.surface, V, V, 0.3);
  const auto      fr = build_friction_constraints<2>(cs, V, 0.3, 5.0, {}, 0.5);
  Eigen::MatrixXd V1 = V;
  V1.rowwise() += Eigen::RowVector2d(0.7, -0.3);
  double expected = 0;
  for (const auto &fc : fr)
    expected += fc.mu * fc.normal_force * 1e-2 / 3;
  EXPECT_NEAR(friction_energy<2>(fr, V1, V, 1e-2), expected, 1e-12 * expected);
  EXPECT_LE(friction_gradient<2>(fr, V1, V, 1e-2).norm(), 1e-10);
}

TEST(Friction, FiniteDifferences2D)
{
  for (int trial = 0; trial < 3; ++trial)
    {
      auto s = scene_2d();
      check_friction_scene<2>(s.surface, s.V(), 0.3);
    }
}

TEST(Friction, FiniteDifferences3D)
{
  for (int trial = 0; trial < 3; ++trial)
    {
      auto s = scene_3d();
      check_friction_scene<3>(s.surface, s.V(), 0.35);
    }
}

TEST(Friction, ProjectedHessianIsPositiveSemiDefinite)
{
  for (int trial = 0; trial < 3; ++trial)
    {
      auto       s  = scene_3d();
      const auto V0 = s.V();
      const auto cs = build_constraints<3>(s.surface, V0, V0, 0.35);
      const auto fr = build_friction_constraints<3>(cs, V0, 0.35, 3.0, {}, 0.5);
      ASSERT_FALSE(fr.empty());
      Eigen::MatrixXd V = V0;
      for (int i = 0; i < V.size(); ++i)
        V(i) += 0.01 * uniform();
      for (const double eps : {1e-4, 1e-2, 1.0})
        {
          const Eigen::MatrixXd H =
            dense(friction_hessian<3>(fr, V, V0, eps, true), static_cast<int>(V.size()));
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
          EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().cwiseAbs().maxCoeff());
          EXPECT_GT(eig.eigenvalues().maxCoeff(), 0.0);
        }
    }
}
