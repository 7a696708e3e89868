// Finite-difference checks of the cell terms (inertia, elasticity for every material,
// gravity) w.r.t. deformed positions x and reference positions u.
#include <ritr/elasticity/bulk_energy.h>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "finite_difference.h"
#include "test_meshes.h"

using namespace ritr;

namespace
{
  template <int dim>
  void check_all_derivatives(const MaterialModel model)
  {
    const SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2);
    Material               material;
    material.model          = model;
    material.youngs_modulus = 1e4;
    material.poisson_ratio  = 0.3;
    material.density        = 900;
    BulkEnergy<dim> energy(mesh, {material});
    CellEnergyWeights<dim> w;
    w.inertia   = 1.0;
    w.potential = 1e-2;
    for (int k = 0; k < dim; ++k)
      w.gravity[k] = -9.81 * (k + 1);
    energy.set_weights(w);
    energy.set_predictor(test_support::deform(mesh.reference, dim, 0.02, 7));

    const Eigen::VectorXd u = mesh.reference;
    const Eigen::VectorXd x = test_support::deform(u, dim, 0.02);
    const Eigen::Index    n = x.size();
    ASSERT_TRUE(std::isfinite(energy.value(x, u)));

    // x: gradient and Hessian of the fast path.
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    energy.add_gradient(x, u, g);
    const auto f_x = [&](const Eigen::VectorXd &y) { return energy.value(y, u); };
    EXPECT_LT(test_support::relative_error(g, test_support::fd_gradient(f_x, x, 1e-6)), 1e-6);
    Triplets h;
    energy.add_hessian(x, u, false, h);
    const auto g_x = [&](const Eigen::VectorXd &y) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
      energy.add_gradient(y, u, r);
      return r;
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(h, n, n), test_support::fd_jacobian(g_x, x, 1e-6)), 1e-6);

    // Joint derivatives agree with the fast path and with differences in u.
    typename BulkEnergy<dim>::JointDerivatives joint;
    energy.joint_derivatives(x, u, ReferenceBlock::exact, joint);
    EXPECT_LT(test_support::relative_error(joint.gx, g), 1e-10);
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.hxx, n, n), test_support::dense(h, n, n)), 1e-10);
    const auto f_u = [&](const Eigen::VectorXd &v) { return energy.value(x, v); };
    EXPECT_LT(test_support::relative_error(joint.gu, test_support::fd_gradient(f_u, u, 1e-7)), 1e-6);
    const auto gu_of_u = [&](const Eigen::VectorXd &v) {
      typename BulkEnergy<dim>::JointDerivatives j;
      energy.joint_derivatives(x, v, ReferenceBlock::exact, j);
      return j.gu;
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.huu, n, n), test_support::fd_jacobian(gu_of_u, u, 1e-7)),
              1e-5);
    const auto gx_of_u = [&](const Eigen::VectorXd &v) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
      energy.add_gradient(x, v, r);
      return r;
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.hxu, n, n), test_support::fd_jacobian(gx_of_u, u, 1e-7)),
              1e-5);

    // Projected blocks are positive semi-definite even under strong compression.
    const Eigen::VectorXd squashed = 0.3 * test_support::deform(u, dim, 0.0);
    Triplets              hp;
    energy.add_hessian(squashed, u, true, hp);
    const Eigen::MatrixXd hd = test_support::dense(hp, n, n);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(hd).eigenvalues().minCoeff(),
              -1e-8 * hd.norm());
  }
} // namespace

TEST(ElasticityDerivatives, NeoHookean1D) { check_all_derivatives<1>(MaterialModel::neo_hookean); }
TEST(ElasticityDerivatives, NeoHookean2D) { check_all_derivatives<2>(MaterialModel::neo_hookean); }
TEST(ElasticityDerivatives, NeoHookean3D) { check_all_derivatives<3>(MaterialModel::neo_hookean); }
TEST(ElasticityDerivatives, Linear1D) { check_all_derivatives<1>(MaterialModel::linear); }
TEST(ElasticityDerivatives, Linear2D) { check_all_derivatives<2>(MaterialModel::linear); }
TEST(ElasticityDerivatives, Linear3D) { check_all_derivatives<3>(MaterialModel::linear); }
TEST(ElasticityDerivatives, StVK2D) { check_all_derivatives<2>(MaterialModel::stvk); }
TEST(ElasticityDerivatives, StVK3D) { check_all_derivatives<3>(MaterialModel::stvk); }

TEST(ElasticityDerivatives, NeoHookeanInversionIsInfinite)
{
  const SimplexMesh<2> mesh = test_support::small_box_mesh<2>(1, 0.0);
  BulkEnergy<2>        energy(mesh, {Material{}});
  Eigen::VectorXd      x = mesh.reference;
  for (Eigen::Index i = 0; i < x.size(); i += 2)
    x[i] = -x[i];  // mirror: every element inverts
  EXPECT_TRUE(std::isinf(energy.value(x, mesh.reference)));
}

TEST(ElasticityDerivatives, RestStateHasZeroElasticForce)
{
  const SimplexMesh<3> mesh = test_support::small_box_mesh<3>(2);
  for (const auto model : {MaterialModel::neo_hookean, MaterialModel::linear, MaterialModel::stvk})
    {
      Material m;
      m.model = model;
      BulkEnergy<3>        energy(mesh, {m});
      CellEnergyWeights<3> w;
      w.inertia = 0;
      energy.set_weights(w);
      Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh.reference.size());
      energy.add_gradient(mesh.reference, mesh.reference, g);
      EXPECT_LT(g.norm(), 1e-8);
      EXPECT_NEAR(energy.value(mesh.reference, mesh.reference), 0.0, 1e-12);
    }
}
