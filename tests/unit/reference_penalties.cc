// Geometric admissibility terms of r-adaptivity: sliding classification of boundary nodes
// (facets, straight 3D edges, corners), the sliding violation and the reference measure
// barrier with finite-difference checks of its gradient and Hessian.
#include <ritr/adaptivity/reference_penalties.h>
#include <ritr/terms/measure_barrier_term.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "finite_difference.h"
#include "test_meshes.h"

using namespace ritr;

namespace
{
  template <int dim>
  std::array<int, 4> count_kinds(const std::vector<SlidingConstraint<dim>> &c)
  {
    std::array<int, 4> n{};
    for (const auto &ci : c)
      n[static_cast<int>(ci.kind)]++;
    return n;
  }
} // namespace

TEST(ReferencePenalties, ClassifiesRectangleAndBox)
{
  BodyDescription r;
  r.shape        = "rectangle";
  r.subdivisions = {3, 2};
  const auto c2  = classify_sliding(build_mesh<2>({r}), 1e-6);
  // 4x3 nodes: 2 interior, 4 corners, 6 sliding on the sides.
  EXPECT_EQ(count_kinds(c2), (std::array<int, 4>{{2, 6, 0, 4}}));

  BodyDescription b;
  b.shape        = "box";
  b.subdivisions = {2, 2, 2};
  const auto c3  = classify_sliding(build_mesh<3>({b}), 1e-6);
  // 27 nodes: 1 interior, 6 face centres, 12 edge midpoints, 8 corners.
  EXPECT_EQ(count_kinds(c3), (std::array<int, 4>{{1, 6, 12, 8}}));
}

template <int dim>
void check_sliding_violation()
{
  const SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2, 0.0);
  const auto             c    = classify_sliding(mesh, 1e-6);
  EXPECT_EQ(sliding_violation(c, mesh.reference), 0.0);
  // Moving every sliding node within its facet (or along its edge) keeps the violation at
  // round-off; a random move does not.
  Eigen::VectorXd along = mesh.reference;
  for (unsigned int i = 0; i < c.size(); ++i)
    {
      Vec<dim> t = Vec<dim>::Zero();
      if (c[i].kind == SlidingKind::edge)
        t = c[i].direction;
      else if (c[i].kind == SlidingKind::facet)
        t = c[i].direction.unitOrthogonal();
      along.template segment<dim>(i * dim) += 0.01 * t;
    }
  EXPECT_LT(sliding_violation(c, along), 1e-15);
  EXPECT_GT(sliding_violation(c, test_support::deform(mesh.reference, dim, 0.02, 5)), 1e-3);
}

TEST(ReferencePenalties, SlidingViolation2D) { check_sliding_violation<2>(); }
TEST(ReferencePenalties, SlidingViolation3D) { check_sliding_violation<3>(); }

template <int dim>
void check_barrier_derivatives()
{
  const SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2, 0.1);
  double                 smallest = 1e30;
  for (const auto &cell : mesh.cells)
    smallest = std::min(smallest, simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell)));
  // Threshold above the smallest elements so that several are inside the barrier's range.
  const double w_hat = 1.5 * smallest;
  const auto   f     = [&](const Eigen::VectorXd &v) { return reference_measure_barrier(mesh, v, w_hat, 2.0); };
  ASSERT_GT(f(mesh.reference), 0.0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh.reference.size());
  Triplets        h;
  reference_measure_barrier(mesh, mesh.reference, w_hat, 2.0, &g, &h, false);
  const double step = 1e-4 * std::pow(smallest, 1.0 / dim);
  EXPECT_LT(test_support::relative_error(g, test_support::fd_gradient(f, mesh.reference, step)), 1e-6);
  const auto grad = [&](const Eigen::VectorXd &v) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(v.size());
    reference_measure_barrier(mesh, v, w_hat, 2.0, &r);
    return r;
  };
  EXPECT_LT(test_support::relative_error(test_support::dense(h, g.size(), g.size()), test_support::fd_jacobian(grad, mesh.reference, step)),
            1e-5);
  // Pushing a node through the opposite facet of its element makes the barrier infinite.
  Eigen::VectorXd flat = mesh.reference;
  const auto     &cell = mesh.cells[0];
  Vec<dim>        opposite = Vec<dim>::Zero();
  for (int a = 1; a <= dim; ++a)
    opposite += mesh.reference_node(cell[a]) / dim;
  flat.template segment<dim>(cell[0] * dim) = opposite + 0.1 * (opposite - mesh.reference_node(cell[0]));
  EXPECT_TRUE(std::isinf(f(flat)));
}

TEST(ReferencePenalties, MeasureBarrierDerivatives1D) { check_barrier_derivatives<1>(); }
TEST(ReferencePenalties, MeasureBarrierDerivatives2D) { check_barrier_derivatives<2>(); }
TEST(ReferencePenalties, MeasureBarrierDerivatives3D) { check_barrier_derivatives<3>(); }
