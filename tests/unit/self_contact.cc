// Self-contact: a thin strip folded into a U whose arms come within dhat of each other
// feels the barrier between primitives of the same body, and CCD stops the arms before
// they touch.
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/mesh/mesh_builder.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace ritr;

TEST(SelfContact, FoldedStripArmsRepelAndCannotCross)
{
  BodyDescription strip;
  strip.shape        = "rectangle";
  strip.upper        = {4, 0.1};
  strip.subdivisions = {80, 2};
  const auto mesh    = build_mesh<2>({strip});
  const double       dhat = 0.02;
  CollisionMesh<2>   contact(mesh, {}, dhat, true);
  ContactBarrierTerm<2> barrier(contact);
  barrier.set_stiffness(1.0);

  // Fold about the top face (y = 0.1), which ends up inside: a point at thickness y lies at
  // radius r(y) = gap/2 + (0.1 - y) from the fold axis, so the arms' inner faces are `gap`
  // apart. The bend takes the length of a half circle at mid-thickness.
  const double    gap = 0.01;
  const double    L   = M_PI * (0.5 * gap + 0.05);
  Eigen::VectorXd z(mesh.reference.size());
  for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
    {
      const double s = mesh.reference[2 * i] - (2 - 0.5 * L);
      const double r = 0.5 * gap + (0.1 - mesh.reference[2 * i + 1]);
      Eigen::Vector2d p;
      if (s < 0)
        p = Eigen::Vector2d(s, -r);  // lower arm
      else if (s > L)
        p = Eigen::Vector2d(-(s - L), r);  // upper arm, folded back over the lower one
      else
        p = Eigen::Vector2d(r * std::sin(M_PI * s / L), -r * std::cos(M_PI * s / L));
      z.segment<2>(2 * i) = p;
    }
  const double d = contact.minimum_distance(z);
  ASSERT_GT(d, 0.0);
  ASSERT_LT(d, dhat);
  EXPECT_GT(barrier.value(TermPoint{z, mesh.reference, contact.candidates_at(z)}), 0.0);  // barrier active between the arms of one body

  // Pressing the upper arm down by twice the gap: CCD keeps the arms apart.
  Eigen::VectorXd dz = Eigen::VectorXd::Zero(z.size());
  for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
    if (z[2 * i + 1] > 0 && z[2 * i] < -0.2)
      dz[2 * i + 1] = -2 * gap;
  const double alpha = contact.max_step(z, dz);
  EXPECT_LT(alpha, 0.5);
  EXPECT_GT(contact.minimum_distance(z + alpha * dz), 0.0);
}
