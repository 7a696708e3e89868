// Finite-difference checks of the assembled r-ITR objective R(x, u) (bulk terms, transferred
// predictor, and the uncorrected inertia's projected-predictor term with its response) in
// 1D and 2D, for every inertia form and predictor projection. The parts are checked on
// their own elsewhere; this checks how the objective composes them.
#include <ritr/adaptivity/ritr_objective.h>

#include <gtest/gtest.h>

#include "finite_difference.h"
#include "test_meshes.h"

#include <random>

using namespace ritr;

namespace
{
  Eigen::VectorXd jitter(const Eigen::VectorXd &u, const double size, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> d(-size, size);
    Eigen::VectorXd                        r = u;
    for (Eigen::Index i = 0; i < r.size(); ++i)
      r[i] += d(rng);
    return r;
  }

  template <int dim>
  void check_objective(const InertiaForm inertia, const PredictorProjection projection)
  {
    const SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(3);
    const Material         material{MaterialModel::neo_hookean, 2e4, 0.3, 800};
    BulkEnergy<dim>        bulk(mesh, {material});
    RitrObjective<dim>     objective(mesh, bulk, nullptr, composite_rule(degree_two_rule<dim>(), 3),
                                 inertia, projection);
    std::array<double, dim> gravity{};
    gravity[dim - 1] = -9.81;
    const Eigen::VectorXd u_t = mesh.reference;
    const Eigen::VectorXd x_t = test_support::deform(u_t, dim, 0.01, 3);
    const Eigen::VectorXd v_t = jitter(Eigen::VectorXd::Zero(u_t.size()), 2.0, 4);
    StepContext<dim> context;
    context.time_step = 1e-2;
    context.gravity   = gravity;
    context.u_start   = u_t;
    context.z_start   = x_t;
    context.v_start   = v_t;
    objective.begin_step(context);

    const Eigen::VectorXd u = jitter(u_t, 0.02, 5);
    const Eigen::VectorXd x = test_support::deform(u, dim, 0.01, 6);
    const Eigen::Index    n = u.size();
    const auto value = [&](const Eigen::VectorXd &y, const Eigen::VectorXd &w) {
      objective.set_candidate(w);
      return objective.value(y, w);
    };
    const auto derivatives = [&](const Eigen::VectorXd &y, const Eigen::VectorXd &w, const ReferenceBlock block) {
      objective.set_candidate(w);
      return objective.derivatives(y, w, block, true);
    };
    const auto d = derivatives(x, u, ReferenceBlock::exact);
    const double step = 1e-6, tolerance = 1e-5;

    // First derivatives against differences of the value.
    const auto r_u = [&](const Eigen::VectorXd &w) { return value(x, w); };
    const auto r_x = [&](const Eigen::VectorXd &y) { return value(y, u); };
    EXPECT_LT(test_support::relative_error(d.gu, test_support::fd_gradient(r_u, u, step)), tolerance);
    EXPECT_LT(test_support::relative_error(d.gx, test_support::fd_gradient(r_x, x, step)), tolerance);

    // Second derivatives against differences of the first.
    const auto g_u = [&](const Eigen::VectorXd &w) { return Eigen::VectorXd(derivatives(x, w, ReferenceBlock::exact).gu); };
    const auto g_x_of_u = [&](const Eigen::VectorXd &w) {
      return Eigen::VectorXd(derivatives(x, w, ReferenceBlock::exact).gx);
    };
    const auto g_x_of_x = [&](const Eigen::VectorXd &y) {
      return Eigen::VectorXd(derivatives(y, u, ReferenceBlock::exact).gx);
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.huu, n, n), test_support::fd_jacobian(g_u, u, step)), tolerance);
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxu, n, n), test_support::fd_jacobian(g_x_of_u, u, step)),
              tolerance);
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxx, n, n), test_support::fd_jacobian(g_x_of_x, x, step)),
              tolerance);

    // The truncated Hessian's block, taken along moves that carry x with u, is the second
    // derivative along those moves for every term that depends on x (the uncorrected
    // inertia's extra term does not, and there that block keeps only its partial Hessian).
    if (inertia == InertiaForm::corrected)
      {
        const auto following = derivatives(x, u, ReferenceBlock::following);
        const auto g_follow  = [&](const Eigen::VectorXd &w) {
          const Eigen::VectorXd y = x + (w - u);
          const auto            e = derivatives(y, w, ReferenceBlock::exact);
          return Eigen::VectorXd(e.gu + e.gx);
        };
        EXPECT_LT(test_support::relative_error(test_support::dense(following.huu, n, n), test_support::fd_jacobian(g_follow, u, step)),
                  tolerance);
      }
  }
} // namespace

TEST(RitrObjectiveDerivatives, Corrected1D) { check_objective<1>(InertiaForm::corrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Uncorrected1D) { check_objective<1>(InertiaForm::uncorrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Corrected2D) { check_objective<2>(InertiaForm::corrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, Uncorrected2D) { check_objective<2>(InertiaForm::uncorrected, PredictorProjection::in_optimization); }
TEST(RitrObjectiveDerivatives, AfterOptimization2D)
{
  check_objective<2>(InertiaForm::uncorrected, PredictorProjection::after_optimization);
}
