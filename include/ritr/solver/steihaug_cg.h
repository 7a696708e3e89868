#pragma once
// The trust-region subproblem min_p g.p + 1/2 p.S p subject to |p|_M <= radius, solved
// approximately by Steihaug's truncated conjugate gradients, preconditioned by M: CG from
// p = 0 until the residual falls below `tolerance`, a direction of non-positive curvature
// appears or an iterate leaves the trust region; the last two end on the region's boundary.
// In the M-norm the iterates' norms grow monotonically, which makes the boundary test exact;
// the norms follow from recurrences, so M itself is never applied, only M^-1.
// S is only applied, never formed, so it may be a Schur complement that costs a
// back-substitution per product.
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <functional>

namespace ritr
{
  using LinearMap = std::function<Eigen::VectorXd(const Eigen::VectorXd &)>;

  struct SteihaugResult
  {
    Eigen::VectorXd step;
    double          predicted_change = 0;  // g.p + 1/2 p.S p (negative)
    bool            interior   = false;  // CG converged inside the region (a Newton step)
    bool            negative_curvature = false;  // stopped on a direction with d.S d <= 0
    double          metric_norm = 0;      // |step|_M
    unsigned int    iterations = 0;       // products with S
  };

  // Inexact Newton's forcing term, CG's residual relative to |g|: it shrinks like
  // sqrt(|g| / |g_0|) (superlinear convergence without oversolving far from the minimum) and
  // is at most `cap`, which each caller sets from what a CG iteration costs it.
  inline double forcing_term(const double gradient_norm, const double first_gradient_norm, const double cap)
  {
    return std::min(cap, std::sqrt(gradient_norm / std::max(first_gradient_norm, 1e-300)));
  }

  // The largest tau >= 0 with |p + tau d|_M <= radius, from p.M p, p.M d and d.M d (p inside
  // the region).
  inline double fraction_to_boundary(const double pMp, const double pMd, const double dMd, const double radius)
  {
    return (-pMd + std::sqrt(std::max(pMd * pMd + dMd * (radius * radius - pMp), 0.0))) / dMd;
  }

  // `precondition` applies M^-1 (empty: M = I).
  SteihaugResult steihaug_cg(const LinearMap &apply, const Eigen::VectorXd &g, double radius, double tolerance,
                             unsigned int max_iterations, const LinearMap &precondition = {});
} // namespace ritr
