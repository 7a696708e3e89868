// Finite-difference checks of the cell terms (elasticity for every material, inertia,
// gravity) w.r.t. deformed positions x and reference positions u.
#include <ritr/step/step_objective.h>
#include <ritr/terms/body_force_term.h>
#include <ritr/terms/elasticity_term.h>
#include <ritr/terms/inertia_term.h>

#include <ritr/common/psd_projection.h>
#include <ritr/elasticity/density_hessian.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include "term_probe.h"
#include "test_meshes.h"

using namespace ritr;

namespace
{
  // A dynamic step of h = 0.1 (potential weight 1e-2) with gravity and a predictor.
  template <int dim>
  StepContext<dim> dynamic_step(const SimplexMesh<dim> &mesh)
  {
    StepContext<dim> step;
    step.time_step = 0.1;
    for (int k = 0; k < dim; ++k)
      step.gravity[k] = -9.81 * (k + 1);
    step.u_start = mesh.reference;
    step.z_start = test_support::deform(mesh.reference, dim, 0.02, 7);
    step.v_start = Eigen::VectorXd::Zero(mesh.reference.size());
    return step;
  }

  template <int dim>
  void check_all_derivatives(const MaterialModel model)
  {
    const SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2);
    Material               material;
    material.model          = model;
    material.youngs_modulus = 1e4;
    material.poisson_ratio  = 0.3;
    material.density        = 900;
    const CellMaterials<dim> materials(mesh, {material});
    TermSum<dim>             terms(mesh, nullptr);
    terms.template add<ElasticityTerm<dim>>(materials);
    terms.template add<InertiaTerm<dim>>(materials, InertiaTerm<dim>::Predictor::nodal, InertiaForm::corrected);
    terms.template add<BodyForceTerm<dim>>(materials);
    terms.begin_step(dynamic_step(mesh));
    const test_support::TermProbe<dim> probe{terms};

    const Eigen::VectorXd u = mesh.reference;
    const Eigen::VectorXd x = test_support::deform(u, dim, 0.02);
    const Eigen::Index    n = x.size();
    ASSERT_TRUE(std::isfinite(probe.energy(x, u)));

    // x: gradient and Hessian of the fast path.
    const Eigen::VectorXd g   = probe.gradient(x, u);
    const auto            f_x = [&](const Eigen::VectorXd &y) { return probe.energy(y, u); };
    EXPECT_LT(test_support::relative_error(g, test_support::fd_gradient(f_x, x, 1e-6)), 1e-6);
    const Eigen::MatrixXd h   = probe.hessian(x, u, false);
    const auto            g_x = [&](const Eigen::VectorXd &y) { return probe.gradient(y, u); };
    EXPECT_LT(test_support::relative_error(h, test_support::fd_jacobian(g_x, x, 1e-6)), 1e-6);

    // Joint derivatives agree with the fast path and with differences in u.
    const auto joint = probe.derivatives(x, u);
    EXPECT_LT(test_support::relative_error(joint.gx, g), 1e-10);
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.hxx, n, n), h), 1e-10);
    const auto f_u = [&](const Eigen::VectorXd &v) { return probe.energy(x, v); };
    EXPECT_LT(test_support::relative_error(joint.gu, test_support::fd_gradient(f_u, u, 1e-7)), 1e-6);
    EXPECT_LT(test_support::relative_error(probe.reference_gradient(x, u), joint.gu), 1e-12);  // the first-order path
    const auto gu_of_u = [&](const Eigen::VectorXd &v) { return Eigen::VectorXd(probe.derivatives(x, v).gu); };
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.huu, n, n), test_support::fd_jacobian(gu_of_u, u, 1e-7)),
              1e-5);
    const auto gx_of_u = [&](const Eigen::VectorXd &v) { return probe.gradient(x, v); };
    EXPECT_LT(test_support::relative_error(test_support::dense(joint.hxu, n, n), test_support::fd_jacobian(gx_of_u, u, 1e-7)),
              1e-5);

    // The following block: the second derivative along moves that carry x with u.
    const auto following = probe.derivatives(x, u, ReferenceBlock::following);
    const auto g_follow  = [&](const Eigen::VectorXd &v) {
      const auto e = probe.derivatives(x + (v - u), v);
      return Eigen::VectorXd(e.gu + e.gx);
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(following.huu, n, n),
                                           test_support::fd_jacobian(g_follow, u, 1e-7)),
              1e-5);

    // Projected blocks are positive semi-definite even under strong compression.
    const Eigen::VectorXd compressed = 0.3 * test_support::deform(u, dim, 0.0);
    const Eigen::MatrixXd hd         = probe.hessian(compressed, u, true);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(hd).eigenvalues().minCoeff(), -1e-8 * hd.norm());
    // The trust-region Newton's one-pass assembly gives the same two Hessians; compression
    // makes the nonlinear models indefinite (a rod stays convex), so the projection has work
    // to do there.
    probe.expect_one_pass_hessians_match(x, u);
    EXPECT_EQ(probe.expect_one_pass_hessians_match(compressed, u), dim > 1 && model != MaterialModel::linear);
    // Newton's generic pair (two separate assemblies) against the step objective's one pass.
    StepObjective<dim> objective(terms);
    objective.begin_iteration(compressed);
    const auto projected = [&](const bool generic) {
      Triplets       h;
      TripletChanges changes;
      if (generic)
        objective.NewtonObjective::hessian_and_projection(compressed, h, changes);
      else
        objective.hessian_and_projection(compressed, h, changes);
      return std::make_pair(test_support::dense(h, n, n), test_support::dense(test_support::with_changes(h, changes), n, n));
    };
    const auto [one_exact, one_projected] = projected(false);
    const auto [two_exact, two_projected] = projected(true);
    EXPECT_EQ((one_exact - two_exact).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE((one_projected - two_projected).cwiseAbs().maxCoeff(), 1e-12 * one_exact.cwiseAbs().maxCoeff());
    // The same for a term's generic one-pass assembly (two more assemblies of the term).
    const auto *elasticity = terms.template find<ElasticityTerm<dim>>();
    const auto  term_pass  = [&](const bool generic) {
      MatrixAssembly<dim> h(mesh.cells);
      const TermPoint     point{compressed, u, {}};
      if (generic)
        elasticity->EnergyTerm<dim>::add_hessian_and_projection(point, h);
      else
        elasticity->add_hessian_and_projection(point, h);
      TripletChanges changes;
      h.append_changes(0, changes);
      const Triplets t = h.to_triplets();
      return std::make_pair(test_support::dense(t, n, n), test_support::dense(test_support::with_changes(t, changes), n, n));
    };
    const auto [term_exact, term_projected]       = term_pass(false);
    const auto [generic_exact, generic_projected] = term_pass(true);
    EXPECT_EQ((term_exact - generic_exact).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE((term_projected - generic_projected).cwiseAbs().maxCoeff(), 1e-12 * term_exact.cwiseAbs().maxCoeff());
  }

  // Statics: elasticity alone, with weight 1.
  template <int dim>
  StepContext<dim> static_step(const SimplexMesh<dim> &mesh)
  {
    StepContext<dim> step;
    step.dynamic = false;
    step.u_start = step.z_start = mesh.reference;
    step.v_start = Eigen::VectorXd::Zero(mesh.reference.size());
    return step;
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

// The analytic eigensystem's projection of d2Psi/dF2 against a numerical eigendecomposition,
// over compressed, stretched, sheared and rotated deformations, with equal and nearly equal
// singular values (where the flip mode's eigenvalue is a limit).
template <int dim>
void check_density_projection(const MaterialModel model)
{
  Material m;
  m.model          = model;
  m.youngs_modulus = 1e4;
  m.poisson_ratio  = 0.4;
  using Square     = Eigen::Matrix<double, dim, dim>;
  std::vector<Eigen::Matrix<double, dim, 1>> stretches;
  for (const double a : {0.3, 0.7, 1.0, 1.0 + 1e-9, 1.4, 2.5})
    for (const double b : {0.5, 1.0, 1.3})
      {
        Eigen::Matrix<double, dim, 1> s = Eigen::Matrix<double, dim, 1>::Constant(b);
        s[0]                            = a;
        stretches.push_back(s);
      }
  if (model == MaterialModel::stvk)
    stretches.push_back(-stretches[1]);  // StVK has no barrier against inversion
  unsigned int changed = 0, seed = 1;
  for (const auto &s : stretches)
    {
      // F = R1 diag(s) R2 with random rotations (QR of random matrices, det fixed to +1).
      const auto rotation = [&]() {
        Square q = Eigen::HouseholderQR<Square>(Square::Random()).householderQ();
        if (q.determinant() < 0)
          q.col(0) *= -1;
        return q;
      };
      std::srand(seed++);
      const Square f = rotation() * s.asDiagonal() * rotation();
      SmallMatrix<dim, double> F;
      for (int k = 0; k < dim; ++k)
        for (int j = 0; j < dim; ++j)
          F[k][j] = f(k, j);
      const DensityHessian<dim> h         = energy_density_hessian<dim>(m, F);
      const auto                change    = density_hessian_projection<dim>(m, F, h);
      const DensityHessian<dim> projected = change ? DensityHessian<dim>(h + *change) : h;
      const DensityHessian<dim> reference = project_to_psd(h);
      EXPECT_LE((projected - reference).cwiseAbs().maxCoeff(), 1e-9 * h.cwiseAbs().maxCoeff())
        << "stretches " << s.transpose();
      changed += change.has_value();
    }
  // Compression makes every nonlinear model indefinite somewhere in the list.
  EXPECT_GT(changed, 2u);
}

TEST(ElasticityDerivatives, DensityProjectionNeoHookean2D) { check_density_projection<2>(MaterialModel::neo_hookean); }
TEST(ElasticityDerivatives, DensityProjectionNeoHookean3D) { check_density_projection<3>(MaterialModel::neo_hookean); }
TEST(ElasticityDerivatives, DensityProjectionStVK2D) { check_density_projection<2>(MaterialModel::stvk); }
TEST(ElasticityDerivatives, DensityProjectionStVK3D) { check_density_projection<3>(MaterialModel::stvk); }

TEST(ElasticityDerivatives, NeoHookeanInversionIsInfinite)
{
  const SimplexMesh<2>   mesh = test_support::small_box_mesh<2>(1, 0.0);
  const CellMaterials<2> materials(mesh, {Material{}});
  ElasticityTerm<2>      elasticity(materials);
  elasticity.begin_step(static_step(mesh));
  Eigen::VectorXd x = mesh.reference;
  for (Eigen::Index i = 0; i < x.size(); i += 2)
    x[i] = -x[i];  // mirror: every element inverts
  EXPECT_TRUE(std::isinf(elasticity.value(TermPoint{x, mesh.reference, {}})));
}

TEST(ElasticityDerivatives, RestStateHasZeroElasticForce)
{
  const SimplexMesh<3> mesh = test_support::small_box_mesh<3>(2);
  for (const auto model : {MaterialModel::neo_hookean, MaterialModel::linear, MaterialModel::stvk})
    {
      Material m;
      m.model = model;
      const CellMaterials<3> materials(mesh, {m});
      ElasticityTerm<3>      elasticity(materials);
      elasticity.begin_step(static_step(mesh));
      const TermPoint rest{mesh.reference, mesh.reference, {}};
      Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh.reference.size());
      elasticity.add_gradient(rest, g);
      EXPECT_LT(g.norm(), 1e-8);
      EXPECT_NEAR(elasticity.value(rest), 0.0, 1e-12);
    }
}
