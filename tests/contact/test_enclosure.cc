// Inside tests of closed components (contact/enclosure.h): closedness, points inside and
// outside convex and non-convex shapes, shapes with holes, and rays that run into a vertex
// or an edge (the direction must change, not the answer).
#include <ritr/contact/enclosure.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace ritr::contact;

namespace
{
  // Rows of a matrix from points.
  Eigen::MatrixXd rows(const std::vector<std::vector<double>> &points)
  {
    Eigen::MatrixXd V(points.size(), points.front().size());
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t k = 0; k < points[i].size(); ++k)
        V(i, k) = points[i][k];
    return V;
  }

  // The closed polygon through vertices first, ..., first + n - 1.
  void add_loop(std::vector<std::array<int, 2>> &segments, const int first, const int n)
  {
    for (int i = 0; i < n; ++i)
      segments.push_back({{first + i, first + (i + 1) % n}});
  }

  // The unit cube [0, 1]^3 as 12 triangles (vertex bit k = coordinate k).
  Eigen::MatrixXd cube_vertices()
  {
    Eigen::MatrixXd V(8, 3);
    for (int i = 0; i < 8; ++i)
      V.row(i) = Eigen::RowVector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    return V;
  }
  const std::vector<std::array<int, 3>> cube_faces = {{{0, 2, 3}}, {{0, 3, 1}}, {{4, 5, 7}}, {{4, 7, 6}},
                                                      {{0, 1, 5}}, {{0, 5, 4}}, {{2, 6, 7}}, {{2, 7, 3}},
                                                      {{0, 4, 6}}, {{0, 6, 2}}, {{1, 3, 7}}, {{1, 7, 5}}};
} // namespace

TEST(Enclosure, ClosedComponents)
{
  std::vector<std::array<int, 2>> square;
  add_loop(square, 0, 4);
  EXPECT_TRUE(is_closed<2>(square));
  square.pop_back();
  EXPECT_FALSE(is_closed<2>(square));  // a polyline, like a row of spikes
  EXPECT_FALSE(is_closed<2>({}));

  EXPECT_TRUE(is_closed<3>(cube_faces));
  auto open_box = cube_faces;
  open_box.pop_back();
  EXPECT_FALSE(is_closed<3>(open_box));
}

TEST(Enclosure, PolygonsWithHolesAndConcaveCorners)
{
  // An L-shaped outline (concave at (1, 1)) with a square hole in its foot.
  const Eigen::MatrixXd V = rows({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3},            // L
                                  {1.5, 0.25}, {2.5, 0.25}, {2.5, 0.75}, {1.5, 0.75}});  // hole
  std::vector<std::array<int, 2>> outline;
  add_loop(outline, 0, 6);
  add_loop(outline, 6, 4);
  ASSERT_TRUE(is_closed<2>(outline));
  EXPECT_TRUE(encloses<2>(V, outline, Eigen::Vector2d(0.5, 2.5)));
  EXPECT_TRUE(encloses<2>(V, outline, Eigen::Vector2d(1.2, 0.5)));
  EXPECT_FALSE(encloses<2>(V, outline, Eigen::Vector2d(2, 2)));    // in the concave corner
  EXPECT_FALSE(encloses<2>(V, outline, Eigen::Vector2d(2, 0.5)));  // in the hole
  EXPECT_FALSE(encloses<2>(V, outline, Eigen::Vector2d(-1, 0.5)));
}

TEST(Enclosure, RaysThroughVerticesChangeDirection)
{
  // A triangle with a vertex on the first ray from p (angle 0.3) and one on its extension
  // backwards: the first rays pass through vertices, and the answer must not depend on it.
  const Eigen::Vector2d p(0.5, 0.5), d(std::cos(0.3), std::sin(0.3));
  const Eigen::MatrixXd V = rows({{p[0] + 2 * d[0], p[1] + 2 * d[1]}, {p[0] - 1, p[1] + 1}, {p[0] - 1, p[1] - 1.5}});
  std::vector<std::array<int, 2>> triangle;
  add_loop(triangle, 0, 3);
  EXPECT_TRUE(encloses<2>(V, triangle, p));
  EXPECT_FALSE(encloses<2>(V, triangle, Eigen::Vector2d(p - 0.5 * d + Eigen::Vector2d(0, 3))));

  // The cube: its centre, a point near one of its edges, points beside it, and one on the
  // line of a face diagonal, where rays through the diagonal's edge are likely.
  const Eigen::MatrixXd C = cube_vertices();
  EXPECT_TRUE(encloses<3>(C, cube_faces, Eigen::Vector3d(0.5, 0.5, 0.5)));
  EXPECT_TRUE(encloses<3>(C, cube_faces, Eigen::Vector3d(0.01, 0.99, 0.5)));
  EXPECT_FALSE(encloses<3>(C, cube_faces, Eigen::Vector3d(1.5, 0.5, 0.5)));
  EXPECT_FALSE(encloses<3>(C, cube_faces, Eigen::Vector3d(-1, -1, -1)));
  EXPECT_FALSE(encloses<3>(C, cube_faces, Eigen::Vector3d(0.5, 2, 0.5)));
}
