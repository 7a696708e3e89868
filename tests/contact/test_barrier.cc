// Barrier function, edge-edge mollifier, assembled barrier potential (gradient and Hessian
// against finite differences in 1D/2D/3D), PSD projection, per-constraint terms and the
// adaptive stiffness rules.
#include <ritr/contact/barrier.h>
#include <ritr/contact/constraints.h>

#include "contact_test_support.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

using ritr::log_barrier;
using ritr::log_barrier_derivative;
using ritr::log_barrier_second_derivative;
using namespace ritr::contact;
using namespace ritr::contact::test_support;

const std::mt19937::result_type ritr::contact::test_support::rng_seed = 99;

namespace
{
  // ---- Small scenes -----------------------------------------------------------------------

  // 1D: rods [a, b] (two vertices each) and obstacle wall points.
  void add_rod(Scene<1> &s, const double a, const double b, const int body)
  {
    s.add_vertex(Vec<1>(a), false, body);
    s.add_vertex(Vec<1>(b), false, body);
  }

  Scene<1> scene_1d()
  {
    Scene<1> s;
    s.add_vertex(Vec<1>(-0.02), true, -1); // wall
    add_rod(s, 0.05, 1.0, 0);
    add_rod(s, 1.08, 2.0, 1);
    add_rod(s, 2.1, 2.5, 2);
    s.add_vertex(Vec<1>(2.6), true, -1); // wall
    return s;
  }

  // Random weights for the surface's weight owners: vertices, and in 3D edges.
  template <int dim>
  ConstraintWeights random_weights(const CollisionSurface<dim> &s)
  {
    return test_support::random_weights(s.n_vertices,
                                        dim == 3 ? static_cast<int>(s.edges.size()) : 0);
  }

  // Central-difference checks of the assembled barrier at V (constraint set fixed).
  template <int dim>
  void expect_barrier_derivatives_match_fd(const std::vector<Constraint> &cs,
                                           const Eigen::MatrixXd &V, const double dhat,
                                           const ConstraintWeights &w, const double tol = 1e-5)
  {
    expect_assembled_derivatives_match_fd(
      [&](const Eigen::MatrixXd &W) { return barrier_energy<dim>(cs, W, dhat, w); },
      [&](const Eigen::MatrixXd &W) { return barrier_gradient<dim>(cs, W, dhat, w); },
      [&](const Eigen::MatrixXd &W) { return barrier_hessian<dim>(cs, W, dhat, w, false); }, V,
      tol);
  }

  // The projected barrier Hessian of the scene (random weights) is PSD; returns whether the
  // unprojected one is indefinite.
  template <int dim>
  bool expect_projected_hessian_psd(const Scene<dim> &s, const double dhat)
  {
    const Eigen::MatrixXd V  = s.V();
    const auto            cs = build_constraints<dim>(s.surface, V, V, dhat);
    const auto            w  = random_weights(s.surface);
    const int             n  = dim * s.surface.n_vertices;
    const Eigen::MatrixXd Hp = dense(barrier_hessian<dim>(cs, V, dhat, w, true), n);
    const Eigen::MatrixXd H  = dense(barrier_hessian<dim>(cs, V, dhat, w, false), n);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Hp), eig_raw(H);
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().cwiseAbs().maxCoeff());
    return eig_raw.eigenvalues().minCoeff() < -1e-8 * H.norm();
  }
} // namespace

// ---- Scalar functions ----------------------------------------------------------------------

TEST(BarrierFunction, DerivativesMatchFiniteDifferences)
{
  const double dhat_sqr = 0.01;
  for (const double d : {1e-6, 1e-4, 1e-3, 5e-3, 9e-3, 9.99e-3})
    {
      const double h = 1e-6 * d;
      EXPECT_NEAR(log_barrier_derivative(d, dhat_sqr),
                  (log_barrier(d + h, dhat_sqr) - log_barrier(d - h, dhat_sqr)) / (2 * h),
                  1e-6 * std::abs(log_barrier_derivative(d, dhat_sqr)) + 1e-12);
      EXPECT_NEAR(log_barrier_second_derivative(d, dhat_sqr),
                  (log_barrier_derivative(d + h, dhat_sqr) -
                   log_barrier_derivative(d - h, dhat_sqr)) /
                    (2 * h),
                  1e-6 * std::abs(log_barrier_second_derivative(d, dhat_sqr)) + 1e-10);
      EXPECT_GT(log_barrier(d, dhat_sqr), 0.0);
      EXPECT_LT(log_barrier_derivative(d, dhat_sqr), 0.0);
      EXPECT_GT(log_barrier_second_derivative(d, dhat_sqr), 0.0);
    }
  // C2 at dhat^2, zero beyond, infinite at contact.
  EXPECT_NEAR(log_barrier(dhat_sqr * (1 - 1e-9), dhat_sqr), 0.0, 1e-20);
  EXPECT_NEAR(log_barrier_derivative(dhat_sqr * (1 - 1e-9), dhat_sqr), 0.0, 1e-12);
  EXPECT_NEAR(log_barrier_second_derivative(dhat_sqr * (1 - 1e-9), dhat_sqr), 0.0, 1e-7);
  EXPECT_EQ(log_barrier(0.02, dhat_sqr), 0.0);
  EXPECT_EQ(log_barrier_derivative(0.02, dhat_sqr), 0.0);
  EXPECT_EQ(log_barrier_second_derivative(0.02, dhat_sqr), 0.0);
  EXPECT_TRUE(std::isinf(log_barrier(0.0, dhat_sqr)));
}

TEST(BarrierFunction, MollifierDerivatives)
{
  const double eps = 0.3;
  for (const double c : {0.0, 0.01, 0.1, 0.2, 0.29})
    {
      const double h = 1e-6;
      EXPECT_NEAR(edge_edge_mollifier_first_derivative(c, eps),
                  (edge_edge_mollifier(c + h, eps) - edge_edge_mollifier(c - h, eps)) / (2 * h),
                  1e-7);
      EXPECT_NEAR(edge_edge_mollifier_second_derivative(c, eps),
                  (edge_edge_mollifier_first_derivative(c + h, eps) -
                   edge_edge_mollifier_first_derivative(c - h, eps)) /
                    (2 * h),
                  1e-6);
    }
  EXPECT_EQ(edge_edge_mollifier(0.0, eps), 0.0);
  EXPECT_NEAR(edge_edge_mollifier(eps * (1 - 1e-12), eps), 1.0, 1e-12);
  EXPECT_NEAR(edge_edge_mollifier_first_derivative(eps * (1 - 1e-12), eps), 0.0, 1e-9);
  EXPECT_EQ(edge_edge_mollifier(2 * eps, eps), 1.0);
}

// ---- Assembled barrier ---------------------------------------------------------------------

TEST(BarrierAssembly, FiniteDifferences1D)
{
  auto                  s    = scene_1d();
  const double          dhat = 0.12;
  const Eigen::MatrixXd V    = s.V();
  const auto            cs   = build_constraints<1>(s.surface, V, V, dhat);
  ASSERT_GE(cs.size(), 4u);
  for (const auto &c : cs)
    {
      EXPECT_EQ(c.kind, ContactKind::vertex_vertex);
      EXPECT_FALSE(s.surface.vertex_is_obstacle(c.first)); // body vertex owns the weight
      EXPECT_EQ(c.weight_index, c.first);
    }
  expect_barrier_derivatives_match_fd<1>(cs, V, dhat, random_weights(s.surface));
}

TEST(BarrierAssembly, FiniteDifferences2D)
{
  for (int trial = 0; trial < 5; ++trial)
    {
      auto                  s    = scene_2d();
      const double          dhat = 0.3;
      const Eigen::MatrixXd V    = s.V();
      const auto            cs   = build_constraints<2>(s.surface, V, V, dhat);
      ASSERT_GE(cs.size(), 3u);
      int n_types[2] = {0, 0};
      for (const auto &c : cs)
        {
          EXPECT_EQ(c.kind, ContactKind::point_edge);
          EXPECT_LT(c.distance_sqr, dhat * dhat);
          ++n_types[c.distance_type == DistanceType::point_line ? 1 : 0];
        }
      EXPECT_GT(n_types[1], 0);
      expect_barrier_derivatives_match_fd<2>(cs, V, dhat, random_weights(s.surface));
    }
}

TEST(BarrierAssembly, FiniteDifferences3D)
{
  int n_pt = 0, n_ee = 0, n_types[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 5; ++trial)
    {
      auto                  s    = scene_3d();
      const double          dhat = 0.35;
      const Eigen::MatrixXd V    = s.V();
      const auto            cs   = build_constraints<3>(s.surface, V, V, dhat);
      ASSERT_GE(cs.size(), 3u);
      for (const auto &c : cs)
        {
          (c.kind == ContactKind::point_triangle ? n_pt : n_ee)++;
          ++n_types[static_cast<int>(c.distance_type)];
          if (c.kind == ContactKind::edge_edge)
            {
              EXPECT_EQ(c.weight_owner, WeightOwner::edge);
              EXPECT_GT(c.mollifier_threshold, 0.0);
            }
        }
      expect_barrier_derivatives_match_fd<3>(cs, V, dhat, random_weights(s.surface));
    }
  EXPECT_GT(n_pt, 0);
  EXPECT_GT(n_ee, 0);
  for (int t = 0; t < 4; ++t)
    EXPECT_GT(n_types[t], 0) << "distance type " << t << " never exercised";
}

TEST(BarrierAssembly, MollifiedNearlyParallelEdges)
{
  // Two nearly parallel edges close to each other: c = |ea x eb|^2 < eps_x, so the
  // mollifier is active; m b must still match finite differences.
  for (const double angle : {1e-2, 1e-3, 3e-3})
    {
      Scene<3> s;
      const int a0 = s.add_vertex(Vec<3>(-1, 0, 0.05), false, 0);
      const int a1 = s.add_vertex(Vec<3>(1, 0, 0.05), false, 0);
      const int b0 = s.add_vertex(Vec<3>(-0.8, -angle, 0), false, 1);
      const int b1 = s.add_vertex(Vec<3>(1.2, angle, 0), false, 1);
      s.surface.edges = {{{a0, a1}}, {{b0, b1}}};
      const Eigen::MatrixXd V    = s.V();
      const double          dhat = 0.1;
      const auto            cs   = build_constraints<3>(s.surface, V, V, dhat);
      ASSERT_EQ(cs.size(), 1u);
      const auto &c = cs[0];
      ASSERT_EQ(c.kind, ContactKind::edge_edge);
      const Vec<3> ea = V.row(a1) - V.row(a0), eb = V.row(b1) - V.row(b0);
      EXPECT_LT(ea.cross(eb).squaredNorm(), c.mollifier_threshold);
      EXPECT_NEAR(c.mollifier_threshold, 1e-3 * ea.squaredNorm() * eb.squaredNorm(), 1e-15);
      // Energy is m b with m < 1.
      const double m = edge_edge_mollifier(ea.cross(eb).squaredNorm(), c.mollifier_threshold);
      EXPECT_LT(m, 1.0);
      EXPECT_NEAR(barrier_energy<3>(cs, V, dhat, {}),
                  m * log_barrier(constraint_distance_sqr<3>(c, V), dhat * dhat), 1e-14);
      expect_barrier_derivatives_match_fd<3>(cs, V, dhat, {}, 2e-5);
    }
}

TEST(BarrierAssembly, ExactlyParallelEdgesAreSwitchedOff)
{
  // Exactly parallel: m = 0 and grad m = 0, so energy and gradient vanish; the Hessian is
  // b * hess(m), which must match finite differences of the gradient.
  Scene<3> s;
  const int a0 = s.add_vertex(Vec<3>(-1, 0, 0.05), false, 0);
  const int a1 = s.add_vertex(Vec<3>(1, 0, 0.05), false, 0);
  const int b0 = s.add_vertex(Vec<3>(-0.8, 0, 0), false, 1);
  const int b1 = s.add_vertex(Vec<3>(1.2, 0, 0), false, 1);
  s.surface.edges = {{{a0, a1}}, {{b0, b1}}};
  const Eigen::MatrixXd V    = s.V();
  const double          dhat = 0.1;
  const auto            cs   = build_constraints<3>(s.surface, V, V, dhat);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(barrier_energy<3>(cs, V, dhat, {}), 0.0);
  EXPECT_EQ(barrier_gradient<3>(cs, V, dhat, {}).norm(), 0.0);
  const Eigen::MatrixXd H = dense(barrier_hessian<3>(cs, V, dhat, {}, false), 12);
  EXPECT_GT(H.norm(), 0.0);
  const Eigen::MatrixXd H_fd = fd_position_jacobian(
    [&](const Eigen::MatrixXd &W) { return barrier_gradient<3>(cs, W, dhat, {}); }, V, 1e-8);
  EXPECT_LE((H - H_fd).norm(), 1e-5 * H.norm());
}

TEST(BarrierAssembly, InactiveAndIntersectingConstraints)
{
  Scene<2> s;
  const int p  = s.add_vertex(Vec<2>(0, 0.05), false, 0);
  const int e0 = s.add_vertex(Vec<2>(-1, 0), false, 1);
  const int e1 = s.add_vertex(Vec<2>(1, 0), false, 1);
  s.surface.edges = {{{e0, e1}}};
  Eigen::MatrixXd V  = s.V();
  const auto      cs = build_constraints<2>(s.surface, V, V, 0.1);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].first, p);
  // Moved out of range: zero contribution, zero derivatives.
  V(p, 1) = 0.5;
  EXPECT_EQ(barrier_energy<2>(cs, V, 0.1, {}), 0.0);
  EXPECT_EQ(barrier_gradient<2>(cs, V, 0.1, {}).norm(), 0.0);
  // Touching: infinite energy.
  V(p, 1) = 0.0;
  EXPECT_TRUE(std::isinf(barrier_energy<2>(cs, V, 0.1, {})));
}

TEST(BarrierAssembly, ProjectedHessianIsPositiveSemiDefinite)
{
  bool saw_indefinite = false;
  for (int trial = 0; trial < 4; ++trial)
    {
      saw_indefinite |= expect_projected_hessian_psd<2>(scene_2d(), 0.3);
      saw_indefinite |= expect_projected_hessian_psd<3>(scene_3d(), 0.35);
    }
  // The test is only meaningful if projection had something to do.
  EXPECT_TRUE(saw_indefinite);
}

TEST(BarrierAssembly, UnweightedTermsReassembleEnergyAndGradient)
{
  auto                  s    = scene_3d();
  const Eigen::MatrixXd V    = s.V();
  const double          dhat = 0.35;
  const auto            cs   = build_constraints<3>(s.surface, V, V, dhat);
  const auto            w    = random_weights(s.surface);
  const auto terms = unweighted_barrier_terms<3>(cs, V, dhat);
  ASSERT_EQ(terms.size(), cs.size());
  double          E = 0.0;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(V.size());
  for (std::size_t k = 0; k < cs.size(); ++k)
    {
      const double wk = cs[k].weight_owner == WeightOwner::vertex ?
                          w.vertex_weights[cs[k].weight_index] :
                          w.edge_weights[cs[k].weight_index];
      EXPECT_EQ(wk, w.weight(cs[k]));
      if (cs[k].weight_owner == WeightOwner::vertex)
        EXPECT_EQ(cs[k].weight_index, cs[k].first); // the point vertex
      else
        EXPECT_EQ(cs[k].weight_index, cs[k].first); // the first edge
      E += wk * terms[k].value;
      ASSERT_EQ(terms[k].gradient.size(), cs[k].n_vertices * 3);
      for (int a = 0; a < cs[k].n_vertices; ++a)
        g.segment<3>(3 * cs[k].vertices[a]) += wk * terms[k].gradient.segment<3>(3 * a);
    }
  EXPECT_NEAR(E, barrier_energy<3>(cs, V, dhat, w), 1e-12 * std::abs(E));
  EXPECT_LE((g - barrier_gradient<3>(cs, V, dhat, w)).norm(), 1e-12 * g.norm());
}

TEST(BarrierAssembly, ObstacleObstaclePairsAreNeverConstraints)
{
  Scene<3> s;
  add_ground(s, 0.0, 1.0);
  // A second obstacle quad just above the first one.
  const int a = s.add_vertex(Vec<3>(-1, -1, 0.01), true, -1);
  const int b = s.add_vertex(Vec<3>(1, -1, 0.01), true, -1);
  const int c = s.add_vertex(Vec<3>(1, 1, 0.01), true, -1);
  s.surface.faces.push_back({{a, b, c}});
  s.surface.edges = edges_of_faces(s.surface.faces);
  const Eigen::MatrixXd V = s.V();
  EXPECT_TRUE(build_constraints<3>(s.surface, V, V, 0.1).empty());
  EXPECT_TRUE(std::isinf(minimum_distance<3>(s.surface, V)));
}

// ---- Adaptive stiffness --------------------------------------------------------------------

TEST(BarrierStiffness, InitialStiffness)
{
  const double bbox = 2.0, dhat = 1e-3, mass = 0.5;
  const double d_ref = 1e-16 * bbox * bbox;
  const double kmin  = 1e11 * mass / (4 * d_ref * log_barrier_second_derivative(d_ref, dhat * dhat));

  // No barrier gradient: kappa_min.
  const Eigen::VectorXd gE = Eigen::VectorXd::LinSpaced(6, -1, 1);
  auto s = initial_barrier_stiffness(bbox, dhat, mass, 1.0, gE, Eigen::VectorXd::Zero(6));
  EXPECT_DOUBLE_EQ(s.kappa_min, kmin);
  EXPECT_DOUBLE_EQ(s.kappa_max, 100 * kmin);
  EXPECT_DOUBLE_EQ(s.kappa, kmin);

  // Barrier gradient opposing the energy gradient: kappa minimises |gE + kappa gB|.
  const Eigen::VectorXd gB = -gE / (10 * kmin);
  s = initial_barrier_stiffness(bbox, dhat, mass, 1.0, gE, gB);
  EXPECT_NEAR(s.kappa, 10 * kmin, 1e-9 * kmin);
  EXPECT_LE((gE + s.kappa * gB).norm(), 1e-9 * gE.norm());

  // Clamped to [kappa_min, kappa_max].
  EXPECT_DOUBLE_EQ(initial_barrier_stiffness(bbox, dhat, mass, 1.0, gE, -gE / (1e3 * kmin)).kappa,
                   100 * kmin);
  EXPECT_DOUBLE_EQ(initial_barrier_stiffness(bbox, dhat, mass, 1.0, gE, gE).kappa, kmin);

  // Weighted constraints: the bounds are per unit weight, so that one constraint of the
  // average weight is as stiff as an unweighted one.
  const double w = 1e-4;
  s              = initial_barrier_stiffness(bbox, dhat, mass, w, gE, Eigen::VectorXd::Zero(6));
  EXPECT_NEAR(s.kappa_min * w, kmin, 1e-12 * kmin);
  EXPECT_NEAR(s.kappa_max * w, 100 * kmin, 1e-12 * kmin);
  EXPECT_NEAR(initial_barrier_stiffness(bbox, dhat, mass, w, gE, w * gB).kappa * w, 10 * kmin, 1e-9 * kmin);
}

TEST(BarrierStiffness, UpdateDoublesOnlyWhenSqueezed)
{
  const double bbox = 1.0, eps = 1e-9 * bbox;
  EXPECT_DOUBLE_EQ(update_barrier_stiffness(0.5 * eps, 0.25 * eps, 10, 100, bbox), 20);
  EXPECT_DOUBLE_EQ(update_barrier_stiffness(0.5 * eps, 0.25 * eps, 80, 100, bbox), 100);
  EXPECT_DOUBLE_EQ(update_barrier_stiffness(0.25 * eps, 0.5 * eps, 10, 100, bbox), 10);
  EXPECT_DOUBLE_EQ(update_barrier_stiffness(2 * eps, 0.5 * eps, 10, 100, bbox), 10);
  EXPECT_DOUBLE_EQ(update_barrier_stiffness(0.5, 0.25, 10, 100, bbox), 10);
}

TEST(BarrierStiffness, BboxDiagonal)
{
  Eigen::MatrixXd V(3, 2);
  V << 0, 0, 3, 1, 1, 4;
  EXPECT_DOUBLE_EQ(bbox_diagonal(V), 5.0);
  EXPECT_EQ(bbox_diagonal(Eigen::MatrixXd(0, 3)), 0.0);
}
