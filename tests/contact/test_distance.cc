// Distance kernels: classification per region, exact derivatives against central finite
// differences, values against an independent projected-gradient minimisation and brute
// force sampling of the primitives.
#include <ritr/contact/distance.h>

#include "contact_test_support.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace ritr::contact;
using namespace ritr::contact::test_support;

const std::mt19937::result_type ritr::contact::test_support::rng_seed = 1234;

namespace
{
  // Random rigid motion, which preserves every classification.
  template <int dim>
  StencilVector<dim> rigid_motion(const StencilVector<dim> &x)
  {
    Eigen::Matrix<double, dim, dim> R = Eigen::Matrix<double, dim, dim>::Identity();
    if constexpr (dim == 3)
      R = Eigen::AngleAxisd(uniform(0, 6.28), random_vector<3>().normalized()).toRotationMatrix();
    if constexpr (dim == 2)
      R = Eigen::Rotation2Dd(uniform(0, 6.28)).toRotationMatrix();
    const Vec<dim>     t = random_vector<dim>();
    StencilVector<dim> y;
    for (int i = 0; i < stencil_size<dim>; ++i)
      y.template segment<dim>(i * dim) = R * x.template segment<dim>(i * dim) + t;
    return y;
  }

  // Gradient and Hessian of distance_sqr against central differences (norm-relative).
  template <int dim>
  void expect_derivatives_match_fd(const ContactKind kind, const StencilVector<dim> &x,
                                   const double tol = 1e-5)
  {
    StencilVector<dim> g;
    StencilMatrix<dim> H;
    const double       d = distance_sqr<dim>(kind, x, g, H);
    EXPECT_NEAR(d, distance_sqr<dim>(kind, x), 1e-14 * (1 + d));
    const double             h    = 1e-6;
    const StencilVector<dim> g_fd = fd_gradient(
      [&](const Eigen::VectorXd &y) { return distance_sqr<dim>(kind, StencilVector<dim>(y)); }, x,
      h);
    const StencilMatrix<dim> H_fd = fd_jacobian(
      [&](const Eigen::VectorXd &y) {
        StencilVector<dim> gy;
        StencilMatrix<dim> Hy;
        distance_sqr<dim>(kind, StencilVector<dim>(y), gy, Hy);
        return Eigen::VectorXd(gy);
      },
      x, h);
    EXPECT_LE((g - g_fd).norm(), tol * std::max(1e-8, g.norm()))
      << "g = " << g.transpose() << "\ng_fd = " << g_fd.transpose();
    EXPECT_LE((H - H_fd).norm(), tol * std::max(1e-8, H.norm())) << "H =\n"
                                                                  << H << "\nH_fd =\n"
                                                                  << H_fd;
  }

  template <int dim>
  void expect_class(const ContactKind kind, const StencilVector<dim> &x, const DistanceType type,
                    const std::vector<int> &slots)
  {
    const DistanceClass cls = classify<dim>(kind, x);
    EXPECT_EQ(static_cast<int>(cls.type), static_cast<int>(type));
    int i = 0;
    for (const int s : slots)
      EXPECT_EQ(cls.slots[i++], s) << "slot " << i - 1;
  }

  // ---- Independent reference distances --------------------------------------------------

  // Minimum of |a + M q|^2 over q in a convex parameter set, by projected gradient descent.
  template <int n, typename Project>
  double projected_gradient_min(const Vec<3> &a, const Eigen::Matrix<double, 3, n> &M,
                                const Project &project)
  {
    const Eigen::Matrix<double, n, n> G    = M.transpose() * M;
    const double                      L    = 2.0 * G.trace() + 1e-300; // >= 2 lambda_max
    Eigen::Matrix<double, n, 1>       q    = project(Eigen::Matrix<double, n, 1>::Constant(0.3));
    for (int it = 0; it < 200000; ++it)
      {
        const Eigen::Matrix<double, n, 1> grad = 2.0 * M.transpose() * (a + M * q);
        const Eigen::Matrix<double, n, 1> next = project(q - grad / L);
        if ((next - q).norm() < 1e-15)
          break;
        q = next;
      }
    return (a + M * q).squaredNorm();
  }

  // Euclidean projection onto the triangle {u, v >= 0, u + v <= 1} of the (u, v) plane.
  Eigen::Vector2d project_to_simplex(const Eigen::Vector2d &q)
  {
    if (q[0] >= 0 && q[1] >= 0 && q[0] + q[1] <= 1)
      return q;
    const Eigen::Vector2d corners[3] = {{0, 0}, {1, 0}, {0, 1}};
    Eigen::Vector2d       best;
    double                best_d = 1e300;
    for (int i = 0; i < 3; ++i)
      {
        const Eigen::Vector2d a = corners[i], e = corners[(i + 1) % 3] - a;
        const double          t = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
        const Eigen::Vector2d c = a + t * e;
        if ((q - c).squaredNorm() < best_d)
          best_d = (q - c).squaredNorm(), best = c;
      }
    return best;
  }

  double reference_point_triangle(const Vec<3> &p, const Vec<3> &t0, const Vec<3> &t1,
                                  const Vec<3> &t2)
  {
    Eigen::Matrix<double, 3, 2> M;
    M << t0 - t1, t0 - t2; // p - (t0 + u e1 + v e2) = (p - t0) + M (u, v)
    return projected_gradient_min<2>(p - t0, M, project_to_simplex);
  }

  double reference_edge_edge(const Vec<3> &a0, const Vec<3> &a1, const Vec<3> &b0,
                             const Vec<3> &b1)
  {
    Eigen::Matrix<double, 3, 2> M;
    M << a1 - a0, b0 - b1; // (a0 + s ea) - (b0 + t eb)
    return projected_gradient_min<2>(a0 - b0, M, [](const Eigen::Vector2d &q) {
      return Eigen::Vector2d(q.cwiseMax(0.0).cwiseMin(1.0));
    });
  }

  // Brute force: minimum over a parameter grid (an upper bound of the distance).
  double sampled_point_triangle(const Vec<3> &p, const Vec<3> &t0, const Vec<3> &t1,
                                const Vec<3> &t2, const int n = 300)
  {
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        best = std::min(best, (p - (t0 + (t1 - t0) * i / double(n) + (t2 - t0) * j / double(n)))
                                .squaredNorm());
    return best;
  }
  double sampled_edge_edge(const Vec<3> &a0, const Vec<3> &a1, const Vec<3> &b0, const Vec<3> &b1,
                           const int n = 300)
  {
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        best = std::min(best,
                        (a0 + (a1 - a0) * i / double(n) - b0 - (b1 - b0) * j / double(n)).squaredNorm());
    return best;
  }

  // point_edge_distance_sqr against brute force over 20001 points of the edge; returns it.
  template <int dim>
  double expect_point_edge_matches_sampling(const Vec<dim> &p, const Vec<dim> &a,
                                            const Vec<dim> &b)
  {
    double best = 1e300;
    for (int i = 0; i <= 20000; ++i)
      best = std::min(best, (p - a - (b - a) * (i / 20000.0)).squaredNorm());
    const double d = point_edge_distance_sqr<dim>(p, a, b);
    EXPECT_LE(d, best + 1e-14);
    EXPECT_NEAR(std::sqrt(d), std::sqrt(best), 1e-4);
    return d;
  }
} // namespace

// ---- Typed kernels with AD ---------------------------------------------------------------

TEST(DistanceKernels, AllTypedKernelsMatchFiniteDifferences)
{
  // Each typed kernel through the classified interface in a configuration that selects it.
  for (int trial = 0; trial < 5; ++trial)
    {
      // 1D vertex-vertex
      expect_derivatives_match_fd<1>(ContactKind::vertex_vertex,
                                     make_stencil<1>({Vec<1>(uniform()), Vec<1>(uniform() + 3)}));
      // 2D point-line (interior region)
      expect_derivatives_match_fd<2>(
        ContactKind::point_edge, rigid_motion<2>(make_stencil<2>({{0.3, 0.4}, {-1, 0}, {1, 0}})));
      // 2D point-point (endpoint regions)
      expect_derivatives_match_fd<2>(
        ContactKind::point_edge, rigid_motion<2>(make_stencil<2>({{-1.5, 0.4}, {-1, 0}, {1, 0}})));
      expect_derivatives_match_fd<2>(
        ContactKind::point_edge, rigid_motion<2>(make_stencil<2>({{1.2, -0.4}, {-1, 0}, {1, 0}})));
    }
}

TEST(DistanceKernels, KernelsDirectlyWithDualNumbers)
{
  // The raw kernels at random points (no classification): AD vs FD.
  constexpr int N    = 12;
  using Dual         = ritr::SecondOrderDual<N>;
  const auto check = [](const auto &f) {
    const auto value = [&](const Eigen::Matrix<double, N, 1> &y) {
      KernelStencil<Dual, 3> yd;
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k)
          yd[i][k] = Dual::variable(3 * i + k, y[3 * i + k]);
      return f(yd);
    };
    Eigen::Matrix<double, N, 1> x = Eigen::Matrix<double, N, 1>::Zero();
    for (int i = 0; i < N; ++i)
      x[i] = uniform();
    const Dual                        d    = value(x);
    const double                      h    = 1e-6;
    const Eigen::Matrix<double, N, 1> g_fd = fd_gradient(
      [&](const Eigen::VectorXd &y) { return value(y).value; }, x, h);
    const Eigen::Matrix<double, N, N> H_fd = fd_jacobian(
      [&](const Eigen::VectorXd &y) { return Eigen::VectorXd(value(y).grad); }, x, h);
    for (int i = 0; i < N; ++i)
      {
        EXPECT_NEAR(d.grad[i], g_fd[i], 1e-5 * std::max(1.0, d.grad.norm()));
        EXPECT_LE((d.hess.col(i) - H_fd.col(i)).norm(), 1e-5 * std::max(1.0, d.hess.norm()));
      }
  };
  for (int trial = 0; trial < 5; ++trial)
    {
      check([](const auto &x) { return kernels::point_point_sqr<Dual, 3>(x[0], x[1]); });
      check([](const auto &x) { return kernels::point_line_sqr<Dual, 3>(x[0], x[1], x[2]); });
      check([](const auto &x) { return kernels::point_plane_sqr<Dual>(x[0], x[1], x[2], x[3]); });
      check([](const auto &x) { return kernels::line_line_sqr<Dual>(x[0], x[1], x[2], x[3]); });
    }
}

// ---- 1D and 2D ---------------------------------------------------------------------------

TEST(Distance1D, VertexVertex)
{
  const StencilVector<1> x(0.25, -1.5);
  EXPECT_DOUBLE_EQ(distance_sqr<1>(ContactKind::vertex_vertex, x), 1.75 * 1.75);
  expect_class<1>(ContactKind::vertex_vertex, x, DistanceType::point_point, {0, 1});
  StencilVector<1> g;
  StencilMatrix<1> H;
  distance_sqr<1>(ContactKind::vertex_vertex, x, g, H);
  EXPECT_DOUBLE_EQ(g[0], 2 * 1.75);
  EXPECT_DOUBLE_EQ(g[1], -2 * 1.75);
  EXPECT_DOUBLE_EQ(H(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(H(0, 1), -2.0);
}

TEST(Distance2D, PointEdgeRegions)
{
  for (int trial = 0; trial < 10; ++trial)
    {
      const auto left  = rigid_motion<2>(make_stencil<2>({{-1.4, 0.3}, {-1, 0}, {1, 0}}));
      const auto mid   = rigid_motion<2>(make_stencil<2>({{0.2, -0.3}, {-1, 0}, {1, 0}}));
      const auto right = rigid_motion<2>(make_stencil<2>({{1.3, 0.6}, {-1, 0}, {1, 0}}));
      expect_class<2>(ContactKind::point_edge, left, DistanceType::point_point, {0, 1});
      expect_class<2>(ContactKind::point_edge, mid, DistanceType::point_line, {0, 1, 2});
      expect_class<2>(ContactKind::point_edge, right, DistanceType::point_point, {0, 2});
      EXPECT_NEAR(distance_sqr<2>(ContactKind::point_edge, left), 0.4 * 0.4 + 0.09, 1e-12);
      EXPECT_NEAR(distance_sqr<2>(ContactKind::point_edge, mid), 0.09, 1e-12);
      EXPECT_NEAR(distance_sqr<2>(ContactKind::point_edge, right), 0.09 + 0.36, 1e-12);
      for (const auto &x : {left, mid, right})
        expect_derivatives_match_fd<2>(ContactKind::point_edge, x);
    }
}

TEST(Distance2D, PointEdgeAgainstSampling)
{
  for (int trial = 0; trial < 200; ++trial)
    {
      const Vec<2> p = random_vector<2>(), a = random_vector<2>(), b = random_vector<2>();
      const double d = expect_point_edge_matches_sampling<2>(p, a, b);
      EXPECT_NEAR(d, distance_sqr<2>(ContactKind::point_edge, make_stencil<2>({p, a, b})), 1e-15);
    }
}

// ---- 3D point-edge (appears inside point-triangle and edge-edge) --------------------------

TEST(Distance3D, PointEdgeAgainstSampling)
{
  for (int trial = 0; trial < 200; ++trial)
    {
      const Vec<3> p = random_vector<3>(), a = random_vector<3>(), b = random_vector<3>();
      expect_point_edge_matches_sampling<3>(p, a, b);
    }
}

// ---- 3D point-triangle: the seven regions --------------------------------------------------

TEST(Distance3D, PointTriangleRegions)
{
  const Vec<3> t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  struct Case
  {
    Vec<3>             p;
    DistanceType       type;
    std::vector<int>   slots;
    double             d;
  };
  const std::vector<Case> cases = {
    {{0.2, 0.2, 0.5}, DistanceType::point_plane, {0, 1, 2, 3}, 0.25},
    {{0.2, 0.2, -0.3}, DistanceType::point_plane, {0, 1, 2, 3}, 0.09},
    {{0.5, -0.3, 0.4}, DistanceType::point_line, {0, 1, 2}, 0.09 + 0.16},
    {{0.8, 0.8, 0.3}, DistanceType::point_line, {0, 2, 3}, 2 * 0.3 * 0.3 + 0.09},
    {{-0.3, 0.5, 0.2}, DistanceType::point_line, {0, 3, 1}, 0.09 + 0.04},
    {{-0.3, -0.3, 0.2}, DistanceType::point_point, {0, 1}, 0.09 + 0.09 + 0.04},
    {{1.4, -0.2, 0.1}, DistanceType::point_point, {0, 2}, 0.16 + 0.04 + 0.01},
    {{-0.2, 1.4, 0.3}, DistanceType::point_point, {0, 3}, 0.04 + 0.16 + 0.09},
  };
  for (int trial = 0; trial < 5; ++trial)
    for (const auto &c : cases)
      {
        SCOPED_TRACE(c.p.transpose());
        const auto x = rigid_motion<3>(make_stencil<3>({c.p, t0, t1, t2}));
        expect_class<3>(ContactKind::point_triangle, x, c.type, c.slots);
        EXPECT_NEAR(distance_sqr<3>(ContactKind::point_triangle, x), c.d, 1e-12);
        expect_derivatives_match_fd<3>(ContactKind::point_triangle, x);
      }
}

TEST(Distance3D, PointTriangleAgainstReference)
{
  for (int trial = 0; trial < 300; ++trial)
    {
      const Vec<3> p = random_vector<3>(), a = random_vector<3>(), b = random_vector<3>(),
                   c = random_vector<3>();
      const double d = point_triangle_distance_sqr(p, a, b, c);
      EXPECT_NEAR(d, reference_point_triangle(p, a, b, c), 1e-10);
      if (trial < 30)
        EXPECT_LE(d, sampled_point_triangle(p, a, b, c) + 1e-14);
    }
}

TEST(Distance3D, PointTriangleDegenerateTriangle)
{
  // Collinear triangle vertices: no plane, the edges decide.
  const Vec<3> p(0.3, 0.4, 0.0), t0(0, 0, 0), t1(1, 0, 0), t2(2, 0, 0);
  EXPECT_NEAR(point_triangle_distance_sqr(p, t0, t1, t2), 0.16, 1e-14);
}

// ---- 3D edge-edge: all regions --------------------------------------------------------------

TEST(Distance3D, EdgeEdgeRegions)
{
  const Vec<3> b0(-1, 0, 0), b1(1, 0, 0);
  struct Case
  {
    Vec<3>           a0, a1;
    DistanceType     type;
    std::vector<int> slots;
    double           d;
    bool             smooth; // differentiable (not exactly parallel)
  };
  const std::vector<Case> cases = {
    // Crossing: interior closest points.
    {{0.2, -1, 0.3}, {0.1, 1, 0.3}, DistanceType::line_line, {0, 1, 2, 3}, 0.09, true},
    // Endpoint of one edge against the interior of the other.
    {{0.2, 0, 0.3}, {0.3, 0.5, 1.2}, DistanceType::point_line, {0, 2, 3}, 0.09, true},
    {{0.3, 0.5, 1.2}, {0.2, 0, 0.3}, DistanceType::point_line, {1, 2, 3}, 0.09, true},
    {{-1.5, -0.5, 0.5}, {-1.5, 0.5, 0.5}, DistanceType::point_line, {2, 0, 1}, 0.5, true},
    {{1.5, -0.5, 0.5}, {1.5, 0.5, 0.5}, DistanceType::point_line, {3, 0, 1}, 0.5, true},
    // Endpoint against endpoint.
    {{-1.2, 0.1, 0.3}, {-2, 0.5, 1}, DistanceType::point_point, {0, 2}, 0.04 + 0.01 + 0.09, true},
    {{1.2, 0.1, 0.3}, {2, 0.5, 1}, DistanceType::point_point, {0, 3}, 0.04 + 0.01 + 0.09, true},
    {{-2, 0.5, 1}, {-1.2, 0.1, 0.3}, DistanceType::point_point, {1, 2}, 0.04 + 0.01 + 0.09, true},
    {{2, 0.5, 1}, {1.2, 0.1, 0.3}, DistanceType::point_point, {1, 3}, 0.04 + 0.01 + 0.09, true},
    // Exactly parallel, overlapping: distance is the line gap, reached on the boundary.
    {{0, 0, 0.3}, {3, 0, 0.3}, DistanceType::point_line, {}, 0.09, false},
    // Exactly parallel, collinear-offset: endpoint to endpoint.
    {{1.5, 0, 0.3}, {2.5, 0, 0.3}, DistanceType::point_point, {0, 3}, 0.25 + 0.09, true},
  };
  for (int trial = 0; trial < 5; ++trial)
    for (const auto &c : cases)
      {
        SCOPED_TRACE(c.a0.transpose());
        const auto x = rigid_motion<3>(make_stencil<3>({c.a0, c.a1, b0, b1}));
        expect_class<3>(ContactKind::edge_edge, x, c.type, c.slots);
        const double d = distance_sqr<3>(ContactKind::edge_edge, x);
        if (c.d >= 0)
          EXPECT_NEAR(d, c.d, 1e-12);
        EXPECT_NEAR(d, reference_edge_edge(c.a0, c.a1, b0, b1), 1e-10);
        if (c.smooth)
          expect_derivatives_match_fd<3>(ContactKind::edge_edge, x);
      }
}

TEST(Distance3D, EdgeEdgeNearlyParallel)
{
  // Angles 1e-3 .. 1e-9: the line-line region is still used when the stationary point is
  // interior, and the value must stay accurate (it is evaluated from explicit closest
  // points, not from the ill-conditioned line-line normal).
  for (int trial = 0; trial < 20; ++trial)
    {
      const double eps = std::pow(10.0, -uniform(3, 9));
      const Vec<3> a0(-1, -eps, 0.2), a1(1, eps, 0.2), b0(-0.9, 0.9 * eps, 0),
                   b1(1.1, -1.1 * eps, 0);
      const auto   x = rigid_motion<3>(make_stencil<3>({a0, a1, b0, b1}));
      // The lines cross in projection inside both edges: the gap between the planes z = 0.2
      // and z = 0 is the exact distance.
      const auto cls = classify<3>(ContactKind::edge_edge, x);
      EXPECT_EQ(cls.type, DistanceType::line_line);
      EXPECT_NEAR(distance_sqr<3>(ContactKind::edge_edge, x), 0.04, 1e-14);

      // Lines crossing (in projection) at x = -1, outside edge c: the minimum is at the end
      // c0 of edge c.
      const Vec<3> c0(0, eps, 0.2), c1(1, 2 * eps, 0.2), e0(-0.9, 0, 0), e1(1.1, 0, 0);
      const auto   y = rigid_motion<3>(make_stencil<3>({c0, c1, e0, e1}));
      EXPECT_NEAR(distance_sqr<3>(ContactKind::edge_edge, y), 0.04 + eps * eps, 1e-14);
    }
}

TEST(Distance3D, EdgeEdgeAgainstReference)
{
  for (int trial = 0; trial < 300; ++trial)
    {
      const Vec<3> a0 = random_vector<3>(), a1 = random_vector<3>(), b0 = random_vector<3>(),
                   b1 = random_vector<3>();
      const double d = edge_edge_distance_sqr(a0, a1, b0, b1);
      EXPECT_NEAR(d, reference_edge_edge(a0, a1, b0, b1), 1e-10);
      if (trial < 30)
        EXPECT_LE(d, sampled_edge_edge(a0, a1, b0, b1) + 1e-14);
    }
}

TEST(Distance3D, RandomConfigurationsMatchFiniteDifferences)
{
  // Random configurations hit all regions; FD must match wherever the type is stable.
  for (int trial = 0; trial < 100; ++trial)
    {
      StencilVector<3> x;
      for (int i = 0; i < 12; ++i)
        x[i] = uniform();
      for (const auto kind : {ContactKind::point_triangle, ContactKind::edge_edge})
        {
          // Skip configurations within FD reach of a region boundary.
          const auto cls = classify<3>(kind, x);
          bool       stable = true;
          for (int i = 0; i < 12 && stable; ++i)
            for (const double s : {-1e-5, 1e-5})
              {
                StencilVector<3> y = x;
                y[i] += s;
                const auto c2 = classify<3>(kind, y);
                stable = stable && c2.type == cls.type && c2.slots == cls.slots;
              }
          if (stable)
            expect_derivatives_match_fd<3>(kind, x);
        }
    }
}

TEST(Distance3D, ClosestPointParameters)
{
  const Vec<3> b0(-1, 0, 0), b1(1, 0, 0);
  const auto   x   = make_stencil<3>({{0.2, -1, 0.3}, {0.2, 1, 0.3}, b0, b1});
  const auto   cls = classify<3>(ContactKind::edge_edge, x);
  const auto   prm = closest_point_parameters<3>(cls, x);
  EXPECT_NEAR(prm[0], 0.5, 1e-14);
  EXPECT_NEAR(prm[1], 0.6, 1e-14);

  const auto y = make_stencil<3>({{0.2, 0.3, 0.7}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const auto c2 = classify<3>(ContactKind::point_triangle, y);
  ASSERT_EQ(c2.type, DistanceType::point_plane);
  const auto q = closest_point_parameters<3>(c2, y);
  EXPECT_NEAR(q[0], 0.2, 1e-14);
  EXPECT_NEAR(q[1], 0.3, 1e-14);
}
