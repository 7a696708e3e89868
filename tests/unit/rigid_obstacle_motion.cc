// Scripted rigid motions of obstacles (rotation about a centre, then translation) and the
// generators' geometry.
#include <ritr/contact/rigid_obstacle.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace ritr::contact;

TEST(RigidObstacleMotion, RotationThenTranslation2D)
{
  RigidObstacle<2> box = make_box<2>(Eigen::Vector2d(1, 0), Eigen::Vector2d(2, 2));
  box.center           = Eigen::Vector2d(1, 0);
  box.angle            = [](double t) { return t * M_PI / 2; };
  box.translation      = [](double t) { return Eigen::Vector2d(0, 3 * t); };
  const auto v         = box.vertices_at(1.0);
  // Corner (0, -1) rotates by 90 degrees about (1, 0) to (2, -1), then moves up by 3.
  EXPECT_NEAR((v[0] - Eigen::Vector2d(2, 2)).norm(), 0.0, 1e-12);
  for (std::size_t i = 0; i < v.size(); ++i)
    EXPECT_NEAR((v[i] - Eigen::Vector2d(1, 3)).norm(), std::sqrt(2.0), 1e-12);  // rigid
}

TEST(RigidObstacleMotion, RotationAboutAxis3D)
{
  RigidObstacle<3> plane = make_plane<3>(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 1, 0), 2.0);
  plane.axis             = Eigen::Vector3d(1, 0, 0);
  plane.angle            = [](double) { return M_PI / 2; };
  for (const auto &p : plane.vertices_at(0.5))
    EXPECT_NEAR(p[2], 0.0, 1e-12);  // the horizontal plane turned vertical about x
}

TEST(RigidObstacleMotion, SpikesHaveTheirHeight)
{
  const auto spikes = make_spikes<2>(Eigen::Vector2d(0, 0), 2.0, 4, 0.3);
  double     top    = 0;
  for (const auto &p : spikes.rest_vertices)
    top = std::max(top, p[1]);
  EXPECT_DOUBLE_EQ(top, 0.3);
  EXPECT_EQ(spikes.edges.size(), 8u);
  const auto spikes3 = make_spikes<3>(Eigen::Vector3d(0, 0, 0), 2.0, 3, 0.3);
  EXPECT_EQ(spikes3.faces.size(), 36u);
}
