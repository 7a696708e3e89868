// Conservative CCD (additive CCD): adversarial tunnelling cases, guaranteed separation,
// reasonable (not absurdly conservative) steps, 1D analytic solution, surface-level
// max_step.
#include <ritr/contact/ccd.h>
#include <ritr/contact/constraints.h>

#include "contact_test_support.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace ritr::contact;
using namespace ritr::contact::test_support;

const std::mt19937::result_type ritr::contact::test_support::rng_seed = 2024;

namespace
{
  template <int dim>
  double distance_at(const ContactKind kind, const StencilVector<dim> &x0,
                     const StencilVector<dim> &x1, const double t)
  {
    return std::sqrt(distance_sqr<dim>(kind, x0 + t * (x1 - x0)));
  }

  // The guarantees of additive_ccd for one pair: d(t) >= s d0, d >= s d0 / 2 on [0, t]
  // (sampled densely), hence never touching.
  template <int dim>
  double checked_ccd(const ContactKind kind, const StencilVector<dim> &x0,
                     const StencilVector<dim> &x1, const double s = 0.1)
  {
    const double t  = additive_ccd<dim>(kind, x0, x1, s);
    const double d0 = distance_at<dim>(kind, x0, x1, 0.0);
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, 1.0);
    EXPECT_GE(distance_at<dim>(kind, x0, x1, t), s * d0 * (1 - 1e-9)) << "t = " << t;
    const int n = 2000;
    for (int i = 0; i <= n; ++i)
      {
        const double ti = t * i / n;
        EXPECT_GE(distance_at<dim>(kind, x0, x1, ti), 0.5 * s * d0 * (1 - 1e-9)) << "t = " << ti;
      }
    return t;
  }
} // namespace

TEST(AdditiveCcd, PointApproachingPlaneIsNotOverlyConservative)
{
  // Distance 1, displacement 2 straight into the plane: contact at t = 0.5.
  const Vec<3> t0(-1, -1, 0), t1(2, -1, 0), t2(-1, 2, 0);
  const auto   x0 = make_stencil<3>({{0.2, 0.2, 1}, t0, t1, t2});
  const auto   x1 = make_stencil<3>({{0.2, 0.2, -1}, t0, t1, t2});
  const double t  = checked_ccd<3>(ContactKind::point_triangle, x0, x1);
  EXPECT_GT(t, 0.4);
  EXPECT_LE(t, 0.5);
  // Same motion split between the point and the triangle.
  const auto y0 = make_stencil<3>({{0.2, 0.2, 1}, t0, t1, t2});
  const Vec<3> up(0, 0, 1);
  const auto y1 = make_stencil<3>({{0.2, 0.2, 0}, t0 + up, t1 + up, t2 + up});
  const double u = checked_ccd<3>(ContactKind::point_triangle, y0, y1);
  EXPECT_GT(u, 0.4);
  EXPECT_LE(u, 0.5);
}

TEST(AdditiveCcd, NoMotionOrSeparatingMotionGivesFullStep)
{
  const auto x0 = make_stencil<2>({{0, 1}, {-1, 0}, {1, 0}});
  EXPECT_EQ(additive_ccd<2>(ContactKind::point_edge, x0, x0), 1.0);
  const auto x1 = make_stencil<2>({{0, 3}, {-1, 0}, {1, 0}});
  EXPECT_EQ(additive_ccd<2>(ContactKind::point_edge, x0, x1), 1.0);
  // Rigid translation of the whole pair.
  const auto x2 = make_stencil<2>({{5, 6}, {4, 5}, {6, 5}});
  EXPECT_EQ(additive_ccd<2>(ContactKind::point_edge, x0, x2), 1.0);
}

TEST(AdditiveCcd, TouchingAtStartGivesZero)
{
  const auto x0 = make_stencil<2>({{0, 0}, {-1, 0}, {1, 0}});
  const auto x1 = make_stencil<2>({{0, -1}, {-1, 0}, {1, 0}});
  EXPECT_EQ(additive_ccd<2>(ContactKind::point_edge, x0, x1), 0.0);
}

TEST(AdditiveCcd, VertexVertex1DIsAnalytic)
{
  // Gap 1, closing speed 2: |d(t)| = 0.1 at t = 0.45.
  EXPECT_NEAR(additive_ccd<1>(ContactKind::vertex_vertex, StencilVector<1>(0, 1),
                              StencilVector<1>(1.5, 0.5)),
              0.45, 1e-15);
  // Reversed order and crossing far beyond: same.
  EXPECT_NEAR(additive_ccd<1>(ContactKind::vertex_vertex, StencilVector<1>(1, 0),
                              StencilVector<1>(-5, 6)),
              0.9 / 12, 1e-15);
  // Separating, or closing but not enough: full step.
  EXPECT_EQ(additive_ccd<1>(ContactKind::vertex_vertex, StencilVector<1>(0, 1),
                            StencilVector<1>(-1, 1)),
            1.0);
  EXPECT_EQ(additive_ccd<1>(ContactKind::vertex_vertex, StencilVector<1>(0, 1),
                            StencilVector<1>(0.5, 1)),
            1.0);
  EXPECT_EQ(additive_ccd<1>(ContactKind::vertex_vertex, StencilVector<1>(0, 0),
                            StencilVector<1>(0.5, 1)),
            0.0);
}

TEST(AdditiveCcd, ThinFastObstacleEdgeCrossingPoint)
{
  // A segment (zero thickness) moves 10 units in one step across a point at distance 0.5:
  // the end positions are both intersection free, only CCD sees the crossing at t = 0.05.
  const auto   x0 = make_stencil<2>({{0, 0}, {-1, 0.5}, {1, 0.5}});
  const auto   x1 = make_stencil<2>({{0, 0}, {-1, -9.5}, {1, -9.5}});
  const double t  = checked_ccd<2>(ContactKind::point_edge, x0, x1);
  EXPECT_LT(t, 0.05);
  EXPECT_GT(t, 0.04);

  // Same with the point grazing the very end of the segment.
  const auto   y0 = make_stencil<2>({{1 + 1e-9, 0}, {-1, 0.5}, {1, 0.5}});
  const auto   y1 = make_stencil<2>({{1 + 1e-9, 0}, {-1, -9.5}, {1, -9.5}});
  const double u  = checked_ccd<2>(ContactKind::point_edge, y0, y1);
  EXPECT_LT(u, 0.05);
}

TEST(AdditiveCcd, RotatingEdgeSweepsThroughPoint)
{
  // Endpoints move linearly so that the edge flips over; it passes the point at t = 0.3.
  const auto   x0 = make_stencil<2>({{0.5, 0.2}, {-1, -1}, {1, 1}});
  const auto   x1 = make_stencil<2>({{0.5, 0.2}, {-1, 1}, {1, -1}});
  const double t  = checked_ccd<2>(ContactKind::point_edge, x0, x1);
  EXPECT_LT(t, 0.3);
  EXPECT_GT(t, 0.1);
}

TEST(AdditiveCcd, VertexGrazingTriangleCorner)
{
  const Vec<3> t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  // Through the corner itself at t = 0.5, and just inside / just outside of it.
  for (const double offset : {0.0, 1e-9, -1e-9, -1e-6})
    {
      const Vec<3> c(offset, offset, 0);
      const auto   x0 = make_stencil<3>({c + Vec<3>(-0.5, -0.5, 0.3), t0, t1, t2});
      const auto   x1 = make_stencil<3>({c + Vec<3>(0.5, 0.5, -0.3), t0, t1, t2});
      const double t  = checked_ccd<3>(ContactKind::point_triangle, x0, x1);
      EXPECT_LT(t, 0.5);
      EXPECT_GT(t, 0.2);
    }
  // Sliding past an edge at 1e-7 in the triangle's plane: the distance drops from 1 to 1e-7,
  // so the step must stop where it reaches 0.1.
  const auto   y0 = make_stencil<3>({{-1, -1e-7, 0}, t0, t1, t2});
  const auto   y1 = make_stencil<3>({{1, -1e-7, 0}, t0, t1, t2});
  const double u  = checked_ccd<3>(ContactKind::point_triangle, y0, y1);
  EXPECT_GT(u, 0.44);
  EXPECT_LE(u, 0.45 + 1e-12);
}

TEST(AdditiveCcd, NearlyParallelEdgesCrossing)
{
  for (const double angle : {0.0, 1e-9, 1e-6, 1e-3})
    {
      // Edge a moves from 0.1 above to 0.1 below edge b (crossing at t = 0.5).
      const auto x0 =
        make_stencil<3>({{-1, 0, 0.1}, {1, angle, 0.1}, {-0.9, 0, 0}, {1.1, -angle, 0}});
      const auto x1 =
        make_stencil<3>({{-1, 0, -0.1}, {1, angle, -0.1}, {-0.9, 0, 0}, {1.1, -angle, 0}});
      const double t = checked_ccd<3>(ContactKind::edge_edge, x0, x1);
      EXPECT_LT(t, 0.5);
      EXPECT_GT(t, 0.4);
      // Also while sliding along each other.
      const auto y1 =
        make_stencil<3>({{-0.5, 0, -0.1}, {1.5, angle, -0.1}, {-0.9, 0, 0}, {1.1, -angle, 0}});
      const double u = checked_ccd<3>(ContactKind::edge_edge, x0, y1);
      EXPECT_LT(u, 0.5);
      EXPECT_GT(u, 0.3);
    }
}

TEST(AdditiveCcd, EdgesCrossingAtRightAngles)
{
  const auto   x0 = make_stencil<3>({{-1, 0, 1}, {1, 0, 1}, {0, -1, 0}, {0, 1, 0}});
  const auto   x1 = make_stencil<3>({{-1, 0, -1}, {1, 0, -1}, {0, -1, 0}, {0, 1, 0}});
  const double t  = checked_ccd<3>(ContactKind::edge_edge, x0, x1);
  EXPECT_GT(t, 0.4);
  EXPECT_LE(t, 0.5);
}

TEST(AdditiveCcd, RandomTrajectoriesKeepSeparation)
{
  int n_limited = 0;
  for (int trial = 0; trial < 300; ++trial)
    {
      StencilVector<3> x0, x1;
      for (int i = 0; i < 12; ++i)
        {
          x0[i] = uniform();
          x1[i] = x0[i] + 2 * uniform();
        }
      for (const auto kind : {ContactKind::point_triangle, ContactKind::edge_edge})
        n_limited += checked_ccd<3>(kind, x0, x1) < 1.0;
      StencilVector<2> y0, y1;
      for (int i = 0; i < 6; ++i)
        {
          y0[i] = uniform();
          y1[i] = y0[i] + 2 * uniform();
        }
      n_limited += checked_ccd<2>(ContactKind::point_edge, y0, y1) < 1.0;
    }
  EXPECT_GT(n_limited, 100);
}

// ---- Surface level -------------------------------------------------------------------------

namespace
{
  struct Scene2
  {
    CollisionSurface<2> surface;
    Eigen::MatrixXd     V;
  };

  // Square body [0,1]^2 and a thin obstacle bar below it.
  Scene2 square_and_bar()
  {
    Scene2 s;
    s.V.resize(6, 2);
    s.V << 0, 0, 1, 0, 1, 1, 0, 1, -5, -0.1, 5, -0.1;
    s.surface.n_vertices  = 6;
    s.surface.edges       = {{{0, 1}}, {{1, 2}}, {{2, 3}}, {{3, 0}}, {{4, 5}}};
    s.surface.is_obstacle = {false, false, false, false, true, true};
    s.surface.body_id     = {0, 0, 0, 0, -1, -1};
    return s;
  }
} // namespace

TEST(MaxStep, SquareFallingThroughThinObstacle)
{
  auto            s  = square_and_bar();
  Eigen::MatrixXd V1 = s.V;
  V1.col(1).head(4).array() -= 10.0; // would end fully below the bar
  const double t = max_step<2>(s.surface, s.V, V1);
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.01);
  const double d0 = minimum_distance<2>(s.surface, s.V);
  const double dt = minimum_distance<2>(s.surface, s.V + t * (V1 - s.V));
  EXPECT_GT(dt, 0.0);
  EXPECT_GE(dt, 0.1 * d0 * (1 - 1e-9));
}

TEST(MaxStep, ObstacleMovingIntoBody)
{
  // The obstacle moves by script (V1 differs on obstacle vertices).
  auto            s  = square_and_bar();
  Eigen::MatrixXd V1 = s.V;
  V1.col(1).tail(2).array() += 3.0;
  const double t = max_step<2>(s.surface, s.V, V1);
  EXPECT_GT(t, 0.02);
  EXPECT_LT(t, 0.1 / 3.0);
  EXPECT_GT(minimum_distance<2>(s.surface, s.V + t * (V1 - s.V)), 0.0);
}

TEST(MaxStep, NoContactGivesFullStep)
{
  auto            s  = square_and_bar();
  Eigen::MatrixXd V1 = s.V;
  V1.col(1).head(4).array() += 1.0;
  EXPECT_EQ(max_step<2>(s.surface, s.V, V1), 1.0);
  EXPECT_EQ(max_step<2>(s.surface, s.V, s.V), 1.0);
}

TEST(MaxStep, OneDimensionalRods)
{
  CollisionSurface<1> s;
  s.n_vertices  = 5;
  s.is_obstacle = {true, false, false, false, false};
  Eigen::MatrixXd V0(5, 1), V1(5, 1);
  V0 << 0, 0.5, 1.5, 2, 3;
  V1 << 0, -1.5, 0, 2, 3; // rod [0.5, 1.5] flies left into the wall
  const double t = max_step<1>(s, V0, V1);
  // Vertex 1 reaches 0.1 * 0.5 from the wall at t = 0.45 / 2.
  EXPECT_NEAR(t, 0.45 / 2.0, 1e-14);
}

TEST(MaxStep, ThreeDimensionalTetrahedronThroughGround)
{
  CollisionSurface<3> s;
  Eigen::MatrixXd     V0(7, 3);
  V0 << 0, 0, 0.05, 1, 0, 0.05, 0, 1, 0.05, 0, 0, 1.05, // tetrahedron just above ground
    -5, -5, 0, 5, -5, 0, 0, 5, 0;                       // ground triangle (obstacle)
  s.n_vertices  = 7;
  s.faces       = {{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{0, 3, 2}}, {{4, 5, 6}}};
  s.edges       = edges_of_faces(s.faces);
  s.is_obstacle = {false, false, false, false, true, true, true};
  Eigen::MatrixXd V1 = V0;
  for (int i = 0; i < 4; ++i)
    V1.row(i) += Eigen::RowVector3d(0.3, 0.2, -3.0); // through the ground
  const double t = max_step<3>(s, V0, V1);
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.05 / 3.0);
  const double dt = minimum_distance<3>(s, V0 + t * (V1 - V0));
  EXPECT_GE(dt, 0.1 * minimum_distance<3>(s, V0) * (1 - 1e-9));
}
