// The trust-region iteration of the Newton driver (HessianProjection::trust_region).
//
// The model is the exact Hessian H; the region and the preconditioner are the projected
// Hessian M (every stencil clamped to its PSD part), which the line-search Newton factorizes
// anyway. H - M lives on the few indefinite stencils only (contact at a sharp corner, a
// compressed element), so CG on M^-1 H converges in about as many iterations as there are
// such stencils, and in one where there are none: the step is then the projected Newton
// step. Where H has negative curvature, Steihaug's CG follows it to the region's edge
// instead of shifting it away, which is what the exact line-search Newton had to do with
// shifts of up to 1e9 at gaps of 1e-12 under a punch's corners (doc/method.md).
#include <ritr/solver/newton.h>
#include <ritr/solver/steihaug_cg.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "free_entries.h"

namespace ritr
{
  using newton_detail::energy_round_off;
  using newton_detail::free_norm;
  using newton_detail::gather_free;
  using newton_detail::scatter_free;

  NewtonSolver::Outcome NewtonSolver::trust_region_iteration(NewtonObjective &objective, Eigen::VectorXd &z,
                                                             const Eigen::VectorXd &g, const std::vector<int> &free_index,
                                                             const double e0, const double shift,
                                                             const NewtonSettings &settings, TrustRegion &region,
                                                             NewtonResult &result)
  {
    const Eigen::Index    n      = z.size();
    const int             n_free = system_.matrix().rows();
    const Eigen::VectorXd g_free = gather_free(g, free_index, n_free);
    const double          gradient_norm = g_free.norm();

    // The region's norm is that of the factorized matrix M (projected Hessian plus `shift`).
    // Shared among processes, each holds its stencils' part of H, and M^-1 is MUMPS' solve.
    const WorkShare *share = settings.work_share && settings.work_share->distributed() ? settings.work_share : nullptr;
    const Eigen::SparseMatrix<double> &H = exact_system_.matrix();
    const LinearMap apply = [&](const Eigen::VectorXd &v) {
      Eigen::VectorXd product = H.selfadjointView<Eigen::Lower>() * v;
      if (share)
        share->sum(product);
      return product;
    };
    const LinearMap precondition = [&](const Eigen::VectorXd &v) {
      const auto            start = std::chrono::steady_clock::now();
      const Eigen::VectorXd r     = share ? distributed_->solve(v) : cholesky_.solve(v);
      linear_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return r;
    };
    // The first region holds the projected Newton step: the line-search iteration's first
    // trial, in the same norm. A start predicted to first order (r-ITR's trial meshes) is
    // trusted further, so that the exact Newton step is taken there.
    if (region.radius == 0)
      {
        region.radius = (settings.start_exact ? 100.0 : 1.0) * std::sqrt(std::max(g_free.dot(precondition(g_free)), 0.0));
        region.first_gradient = gradient_norm;
      }
    // CG iterations cost a back-substitution each, so the forcing term's cap is tight: at
    // 0.1 the solves from r-ITR's predicted states took one step more (2,886 against 1,770
    // inner iterations on the ball on spikes).
    const double forcing = forcing_term(gradient_norm, region.first_gradient, 1e-3);
    const double round_off = energy_round_off(e0);
    const double position_round_off = 4 * std::numeric_limits<double>::epsilon() * z.lpNorm<Eigen::Infinity>();

    Eigen::VectorXd dz(n), trial, trial_gradient(n);
    for (;;)
      {
        ++result.line_search_trials;
        const SteihaugResult cg = steihaug_cg(apply, g_free, region.radius, forcing * gradient_norm, 200, precondition);
        dz.setZero();
        scatter_free(cg.step, free_index, dz);
        result.last_step_norm = objective.step_norm(dz);
        result.energy         = e0;
        if (cg.interior && result.last_step_norm <= settings.tolerance)
          return Outcome::converged;
        if (result.last_step_norm < position_round_off)
          {
            // The region collapsed below the positions' round-off without a decrease.
            if (settings.round_off_stall_converges && std::abs(cg.predicted_change) <= 1e-12 * std::max(1.0, std::abs(e0)))
              return Outcome::converged;
            result.status  = NewtonStatus::line_search_failed;
            result.failure = "trust region collapsed below the positions' round-off";
            return Outcome::failed;
          }
        // The part of the step CCD certifies, and the model's change over that part.
        const double    ccd_bound = std::min(1.0, objective.max_step(z, dz));
        // CG tracked the model's change g.p + 1/2 p.H p along the way: no product with H here.
        const double    slope = g_free.dot(cg.step), curvature = 2 * (cg.predicted_change - slope);
        const double    predicted = ccd_bound * slope + 0.5 * ccd_bound * ccd_bound * curvature;
        const double    step_length = ccd_bound * cg.metric_norm;
        trial               = z + ccd_bound * dz;
        const double e      = objective.value(trial);
        bool accepted = false, judged_by_gradient = false;
        double       ratio  = -std::numeric_limits<double>::infinity();
        if (std::isfinite(e))
          {
            if (-predicted > round_off)
              {
                ratio    = (e - e0) / predicted;
                accepted = ratio >= 0.05;
              }
            else
              {
                // The energy cannot resolve the step; the gradient can (as in the line search).
                judged_by_gradient = true;
                trial_gradient.setZero();
                objective.gradient(trial, trial_gradient);
                accepted = free_norm(trial_gradient, free_index) < gradient_norm;
                ratio    = accepted ? 1.0 : 0.0;
              }
          }
        if (ratio < 0.25)
          region.radius = 0.25 * step_length;
        else if (ratio > 0.75 && ccd_bound == 1.0 && !cg.interior)
          region.radius *= 2;
        if (!accepted)
          continue;
        region.cg_iterations = cg.iterations;
        z = trial;
        objective.accept(z);
        if (settings.monitor)
          {
            NewtonIterationRecord record{result.iterations, e0, e - e0, predicted, result.last_step_norm, gradient_norm,
                                         ccd_bound, ccd_bound, false, judged_by_gradient, shift, true};
            record.trust_radius  = region.radius;
            record.cg_iterations = cg.iterations;
            settings.monitor(record, z);
          }
        return Outcome::accepted;
      }
  }
} // namespace ritr
