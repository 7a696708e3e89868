// Finite-difference checks of the assembled r-ITR objective R(x, u) (elasticity, gravity,
// inertia with the transferred predictor, and the uncorrected inertia's projected-predictor
// term with its response) in 1D and 2D, for every inertia form and predictor projection, and
// of the first-order path to g_u alone against the second-order one. The terms are checked on
// their own elsewhere; this checks how their sum composes them.
#include <ritr/adaptivity/ritr_options.h>
#include <ritr/terms/body_force_term.h>
#include <ritr/terms/elasticity_term.h>
#include <ritr/terms/transferred_inertia_term.h>

#include <gtest/gtest.h>

#include "term_probe.h"
#include "test_meshes.h"

using namespace ritr;

namespace
{
  template <int dim>
  void check_objective(const InertiaForm inertia, const PredictorProjection projection,
                       const transfer::TransferIntegration integration = transfer::TransferIntegration::quadrature)
  {
    const SimplexMesh<dim>   mesh = test_support::small_box_mesh<dim>(3);
    const Material           material{MaterialModel::neo_hookean, 2e4, 0.3, 800};
    const CellMaterials<dim> materials(mesh, {material});
    TermSum<dim>             terms(mesh, nullptr);
    terms.template add<ElasticityTerm<dim>>(materials);
    if (projection == PredictorProjection::in_optimization)
      terms.template add<TransferredInertiaTerm<dim>>(materials, composite_rule(degree_two_rule<dim>(), 3), inertia,
                                                       integration);
    else
      terms.template add<InertiaTerm<dim>>(materials, InertiaTerm<dim>::Predictor::nodal, inertia);
    terms.template add<BodyForceTerm<dim>>(materials);
    StepContext<dim> context;
    context.time_step         = 1e-2;
    context.gravity[dim - 1]  = -9.81;
    context.u_start           = mesh.reference;
    context.z_start           = test_support::deform(context.u_start, dim, 0.01, 3);
    context.v_start           = test_support::jitter(Eigen::VectorXd::Zero(context.u_start.size()), 2.0, 4);
    terms.begin_step(context);
    const test_support::TermProbe<dim> probe{terms};

    const Eigen::VectorXd u = test_support::jitter(context.u_start, 0.02, 5);
    const Eigen::VectorXd x = test_support::deform(u, dim, 0.01, 6);
    const Eigen::Index    n = u.size();
    const auto            d = probe.derivatives(x, u);
    const double step = 1e-6, tolerance = 1e-5;

    // First derivatives against differences of the value.
    const auto r_u = [&](const Eigen::VectorXd &w) { return probe.objective(x, w); };
    const auto r_x = [&](const Eigen::VectorXd &y) { return probe.objective(y, u); };
    EXPECT_LT(test_support::relative_error(d.gu, test_support::fd_gradient(r_u, u, step)), tolerance);
    EXPECT_LT(test_support::relative_error(d.gx, test_support::fd_gradient(r_x, x, step)), tolerance);
    // The first-order path (the Eshelby stress, first-order duals on the exact transfer) gives
    // the same g_u to round-off.
    EXPECT_LT(test_support::relative_error(probe.reference_gradient(x, u), d.gu), 1e-12);

    // Second derivatives against differences of the first.
    const auto g_u      = [&](const Eigen::VectorXd &w) { return Eigen::VectorXd(probe.derivatives(x, w).gu); };
    const auto g_x_of_u = [&](const Eigen::VectorXd &w) { return Eigen::VectorXd(probe.derivatives(x, w).gx); };
    const auto g_x_of_x = [&](const Eigen::VectorXd &y) { return Eigen::VectorXd(probe.derivatives(y, u).gx); };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.huu, n, n), test_support::fd_jacobian(g_u, u, step)),
              tolerance);
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxu, n, n), test_support::fd_jacobian(g_x_of_u, u, step)),
              tolerance);
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxx, n, n), test_support::fd_jacobian(g_x_of_x, x, step)),
              tolerance);

    // The truncated Hessian's block, taken along moves that carry x with u, is the second
    // derivative along those moves for every term that depends on x (the uncorrected
    // inertia's extra term does not, and there that block keeps only its partial Hessian).
    if (inertia == InertiaForm::corrected)
      {
        const auto following = probe.derivatives(x, u, ReferenceBlock::following);
        const auto g_follow  = [&](const Eigen::VectorXd &w) {
          const auto e = probe.derivatives(x + (w - u), w);
          return Eigen::VectorXd(e.gu + e.gx);
        };
        EXPECT_LT(test_support::relative_error(test_support::dense(following.huu, n, n),
                                               test_support::fd_jacobian(g_follow, u, step)),
                  tolerance);
      }
  }
} // namespace

TEST(RitrObjectiveDerivatives, Corrected1D) { check_objective<1>(InertiaForm::corrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Uncorrected1D) { check_objective<1>(InertiaForm::uncorrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Corrected2D) { check_objective<2>(InertiaForm::corrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Uncorrected2D) { check_objective<2>(InertiaForm::uncorrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, CorrectedExactTransfer2D)
{
  check_objective<2>(InertiaForm::corrected, PredictorProjection::in_optimization, transfer::TransferIntegration::exact);
}
TEST(RitrObjectiveDerivatives, UncorrectedExactTransfer2D)
{
  check_objective<2>(InertiaForm::uncorrected, PredictorProjection::in_optimization, transfer::TransferIntegration::exact);
}
TEST(RitrObjectiveDerivatives, AfterOptimization2D)
{
  check_objective<2>(InertiaForm::uncorrected, PredictorProjection::after_optimization);
}
