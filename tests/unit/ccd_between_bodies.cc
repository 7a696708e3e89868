// Regression: two identical disks moving head-on so that two vertices meet exactly (a
// perfectly symmetric vertex-vertex impact). Continuous collision detection must stop the
// step before they touch.
#include <ritr/contact/collision_mesh.h>
#include <ritr/mesh/mesh_builder.h>

#include <gtest/gtest.h>

using namespace ritr;

TEST(CcdBetweenBodies, SymmetricHeadOnVertexImpact)
{
  BodyDescription left;
  left.shape             = "disk";
  left.radius            = 0.3;
  left.shape_refinements = 2;
  left.center            = {-0.33, 0.5};
  BodyDescription right  = left;
  right.center           = {0.33, 0.5};
  const auto mesh        = build_mesh<2>({left, right});
  CollisionMesh<2> contact(mesh, {}, 1e-3, true);

  Eigen::VectorXd z = mesh.reference, dz = Eigen::VectorXd::Zero(z.size());
  for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
    dz[2 * i] = mesh.reference[2 * i] < 0 ? 0.03 : -0.03;  // each closes 0.03 of the 0.06 gap
  const double alpha = contact.max_step(z, dz);
  EXPECT_LT(alpha, 1.0);
  // At least the guaranteed tenth of the 0.06 start gap remains.
  EXPECT_GT(contact.minimum_distance(z + alpha * dz), 0.1 * 0.06 * (1 - 1e-9));
}
