// Paper Fig. 7: choice of the inertial energy. A rod on [0, 1] with nodes (0, a, 1), the left
// end held, moving with v(X) = -4 X^2 (prm/verification/ritr/inertia_1d.prm), one step of
// h = 1e-2. The test scans the reduced objective R*(a) = min_x R(x, a) with exact integration
// (written here, independent of the solver and its quadrature) and asserts:
//  - corrected inertia (eq. 10): R* has an interior minimum, and r-ITR ends there;
//  - uncorrected inertia (eq. 8): R* is smallest near a degenerate element, and r-ITR drifts
//    there from the uniform mesh;
// both for the full and the truncated outer Hessian.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <iostream>

#include "ritr_scenes.h"

using namespace ritr;
using namespace ritr::test_support;

namespace
{
  constexpr double rho = 1e3, E = 2e5, h = 1e-2;

  // The predictor x_t + h v_t, linear between the start-of-step nodes 0, 1/2, 1.
  double predictor(const double X)
  {
    const auto node = [](const double Y) { return Y - h * 4 * Y * Y; };
    return X <= 0.5 ? node(0.5) * X / 0.5 : node(0.5) + (node(1.0) - node(0.5)) * (X - 0.5) / 0.5;
  }

  // R*(a) with the left node held at 0. The transfer integrals int phi_i x_pred are piecewise
  // quadratic between the breakpoints {0, a, 1/2, 1}, so Simpson's rule on each piece is exact.
  double reduced_objective(const double a, const bool corrected)
  {
    const std::array<double, 3> X{{0, a, 1}};
    const auto hat = [&](const int i, const double Y) {
      if (i > 0 && Y >= X[i - 1] && Y <= X[i])
        return (Y - X[i - 1]) / (X[i] - X[i - 1]);
      if (i < 2 && Y >= X[i] && Y <= X[i + 1])
        return (X[i + 1] - Y) / (X[i + 1] - X[i]);
      return 0.0;
    };
    std::vector<double> breaks{0, a, 0.5, 1};
    std::sort(breaks.begin(), breaks.end());
    Eigen::Vector3d b = Eigen::Vector3d::Zero();  // int phi_i x_pred (unit density)
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
      {
        const double l = breaks[k], r = breaks[k + 1], m = 0.5 * (l + r);
        for (int i = 0; i < 3; ++i)
          b[i] += (r - l) / 6 *
                  (hat(i, l) * predictor(l) + 4 * hat(i, m) * predictor(m) + hat(i, r) * predictor(r));
      }
    Eigen::Matrix3d mass = Eigen::Matrix3d::Zero(), stiffness = Eigen::Matrix3d::Zero();
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (int e = 0; e < 2; ++e)
      {
        const double L = X[e + 1] - X[e];
        mass.block<2, 2>(e, e) += L / 6 * Eigen::Matrix2d{{2, 1}, {1, 2}};
        stiffness.block<2, 2>(e, e) += h * h * E / L * Eigen::Matrix2d{{1, -1}, {-1, 1}};
        force.segment<2>(e) += h * h * E * Eigen::Vector2d(-1, 1);  // from (E/2) L (dx/L - 1)^2
      }
    // R(x) = 1/2 x^T (rho M + K) x - (rho b + f)^T x + h^2 E / 2, x_0 = 0.
    const Eigen::Matrix3d A = rho * mass + stiffness;
    const Eigen::Vector3d l = rho * b + force;
    Eigen::Vector3d       x = Eigen::Vector3d::Zero();
    x.tail<2>()             = A.bottomRightCorner<2, 2>().ldlt().solve(l.tail<2>());
    double value            = 0.5 * x.dot(A * x) - l.dot(x) + h * h * E / 2;
    if (!corrected)
      value += 0.5 * rho * b.dot(mass.ldlt().solve(b));  // 1/2 rho pi^T M pi, M pi = b
    return value;
  }

  // The minimiser of R* over (0, 1): a grid, then golden sections around its best point.
  double reduced_minimiser(const bool corrected)
  {
    const auto f    = [&](const double a) { return reduced_objective(a, corrected); };
    double     best = 0.01;
    for (double a = 0.01; a < 0.995; a += 0.01)
      best = f(a) < f(best) ? a : best;
    double       lo = std::max(best - 0.01, 1e-4), hi = std::min(best + 0.01, 1 - 1e-4);
    const double g  = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 100; ++it)
      {
        const double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
        (f(c) < f(d) ? hi : lo) = f(c) < f(d) ? d : c;
      }
    return 0.5 * (lo + hi);
  }

  // The middle reference node after one r-ITR step of the scene.
  double ritr_middle_node(const std::string &inertia, const std::string &hessian)
  {
    Scene scene                = ritr_scene("inertia_1d.prm");
    scene.adaptivity.inertia   = inertia_form_from(inertia);
    scene.adaptivity.hessian   = ritr_hessian_from(hessian);
    const auto            s    = run_scene<1>(scene);
    std::vector<double>   u(s->reference().data(), s->reference().data() + s->reference().size());
    std::sort(u.begin(), u.end());
    const auto &record = s->history().back();
    std::cout << inertia << ", " << hessian << " Hessian: middle node " << u[1] << " after "
              << record.outer_iterations << " outer iterations" << std::endl;
    EXPECT_TRUE(s->invariant_violations().empty());
    return u[1];
  }
} // namespace

TEST(RitrInertia1D, CorrectedInertiaHasAnInteriorOptimum)
{
  const double a = reduced_minimiser(true);
  std::cout << "corrected: R* smallest at a = " << a << "; R*(0.05) - R*(a) = "
            << reduced_objective(0.05, true) - reduced_objective(a, true)
            << ", R*(0.95) - R*(a) = " << reduced_objective(0.95, true) - reduced_objective(a, true) << std::endl;
  // A basin well inside (0, 1): both near-degenerate meshes are clearly worse.
  EXPECT_GT(a, 0.3);
  EXPECT_LT(a, 0.5);
  EXPECT_GT(reduced_objective(0.05, true) - reduced_objective(a, true), 1e-3);
  EXPECT_GT(reduced_objective(0.95, true) - reduced_objective(a, true), 1e-3);
  // r-ITR finds it (the quadrature's kinks leave it within a few thousandths).
  for (const std::string hessian : {"full", "truncated"})
    EXPECT_NEAR(ritr_middle_node("corrected", hessian), a, 5e-3) << hessian;
}

TEST(RitrInertia1D, UncorrectedInertiaDriftsToADegenerateElement)
{
  const double a = reduced_minimiser(false);
  std::cout << "uncorrected: R* smallest at a = " << a << " (element length ratio " << a / (1 - a) << ")"
            << std::endl;
  EXPECT_LT(a / (1 - a), 0.1);
  for (const std::string hessian : {"full", "truncated"})
    {
      const double middle = ritr_middle_node("uncorrected", hessian);
      EXPECT_LT(middle / (1 - middle), 0.1) << hessian;
      EXPECT_NEAR(middle, a, 5e-3) << hessian;
    }
}
