#include <ritr/solver/newton.h>

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

  namespace
  {
    // CG iterations with a reused factor after which the next iteration factorizes afresh: at
    // 44K 3D vertices a back-substitution costs about 1/100 of a factorization in wall time.
    constexpr unsigned int reused_factor_cg_limit = 20;
  } // namespace

  NewtonResult NewtonSolver::minimize(NewtonObjective &objective, Eigen::VectorXd &z,
                                      const std::vector<bool> &kinematic,
                                      const Eigen::VectorXd &targets, const NewtonSettings &settings)
  {
    const Eigen::Index n = z.size();
    std::vector<int>   free_index(n, -1);
    int                n_free = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!kinematic[i])
        free_index[i] = n_free++;

    // Shared among processes: Trilinos solves the projected Newton system, or with the direct
    // solver preconditions the trust region's CG; the shifted exact Hessian needs CHOLMOD's
    // factor, and the trust region an exact inverse of the projected Hessian.
    const bool distributed = settings.work_share && settings.work_share->distributed();
    std::vector<int> free_entry;
    if (distributed)
      {
        const bool trust_region_direct = settings.projection == HessianProjection::trust_region &&
                                         settings.distributed_solver == DistributedSolver::direct;
        if (settings.projection != HessianProjection::always && !trust_region_direct)
          throw std::logic_error("NewtonSolver: a shared run takes projected Newton, or the trust region with the direct solver");
        if (!distributed_)
          distributed_ = std::make_unique<DistributedLinearSystem>(*settings.work_share, settings.distributed_solver);
        free_entry.resize(n_free);
        for (Eigen::Index i = 0; i < n; ++i)
          if (free_index[i] >= 0)
            free_entry[free_index[i]] = static_cast<int>(i);
      }

    NewtonResult    result;
    Eigen::VectorXd g(n), dz(n);
    Triplets        h;
    // Adaptive projection: projected Newton until it crawls, then the exact Hessian.
    bool         adaptive = settings.projection == HessianProjection::adaptive;  // may still switch
    bool         exact    = settings.projection == HessianProjection::never || (adaptive && settings.start_exact);
    unsigned int crawling = 0;
    double       last_full_step  = std::numeric_limits<double>::infinity();
    TrustRegion  region;
    double       shift = 0;  // of the last factorization

    for (result.iterations = 0; result.iterations < settings.max_iterations; ++result.iterations)
      {
        objective.begin_iteration(z);
        const double e0 = objective.value(z);
        if (!std::isfinite(e0))
          {
            result.status  = NewtonStatus::not_finite;
            result.failure = "the energy is not finite at the start of the iteration";
            return result;
          }
        g.setZero();
        objective.gradient(z, g);
        // Prescribed part of the step, then the free part from
        // H_ff dz_f = -g_f - H_fk dz_k.
        dz.setZero();
        bool kinematic_pending = false;
        for (Eigen::Index i = 0; i < n; ++i)
          if (kinematic[i])
            {
              dz[i] = targets[i] - z[i];
              kinematic_pending |= dz[i] != 0.0;
            }
        Eigen::VectorXd rhs          = -gather_free(g, free_index, n_free);
        const bool      trust_region = settings.projection == HessianProjection::trust_region && !kinematic_pending;
        if (trust_region)
          {
            // The model's exact Hessian and the projected one it is preconditioned with, from
            // one evaluation of the stencils.
            exact_triplets_.clear();
            projection_changes_.clear();
            objective.hessian_and_projection(z, exact_triplets_, projection_changes_);
            exact_system_.assemble(exact_triplets_, free_index, n_free, dz, rhs);
            system_.assemble_changed(exact_system_, projection_changes_);
          }
        else
          {
            h.clear();
            objective.hessian(z, h, !exact);
            // Shared among processes, these are this process's entries: their coupling to the
            // prescribed step is summed over the processes like the gradient was.
            Eigen::VectorXd coupling;
            if (distributed)
              coupling.setZero(n_free);
            system_.assemble(h, free_index, n_free, dz, distributed ? coupling : rhs);
            if (distributed)
              {
                settings.work_share->sum(coupling);
                rhs += coupling;
              }
          }
        auto start = std::chrono::steady_clock::now();
        // A large factor of an earlier iteration preconditions this one's CG while it keeps
        // CG short: the exact Hessian is this iteration's, so only CG's iteration count changes.
        const bool reuse_factor = trust_region && !distributed && region.radius > 0 &&
                                  region.cg_iterations <= reused_factor_cg_limit &&
                                  cholesky_.factorization_flops() >= settings.reuse_factorizations_from;
        if (distributed)
          distributed_->factorize(system_.matrix(), free_entry);
        else if (!reuse_factor)
          shift = cholesky_.factorize(system_.matrix());
        linear_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (trust_region)
          {
            const Outcome outcome =
              trust_region_iteration(objective, z, g, free_index, e0, shift, settings, region, result);
            if (outcome == Outcome::converged)
              result.status = NewtonStatus::converged;
            if (outcome != Outcome::accepted)
              return result;
            continue;
          }
        start                         = std::chrono::steady_clock::now();
        const Eigen::VectorXd dz_free = distributed ? distributed_->solve(rhs) : cholesky_.solve(rhs);
        linear_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        scatter_free(dz_free, free_index, dz);

        objective.limit_step(z, dz);
        result.last_step_norm = objective.step_norm(dz);
        result.energy         = e0;
        // A step from a shifted Hessian is small because of the shift, not because z is near
        // the minimum (the barrier's negative curvature at tiny gaps forces huge shifts): it
        // does not count as converged.
        if (!kinematic_pending && result.last_step_norm <= settings.tolerance && !(exact && shift > 0))
          {
            result.status = NewtonStatus::converged;
            return result;
          }

        // Backtracking from the CCD-certified step. While prescribed entries are still
        // moving the direction need not be a descent direction, so only finiteness (no
        // inversion) is required then; afterwards Armijo's sufficient decrease -- judged on
        // the gradient norm once the predicted decrease is below the energy's round-off.
        const double ccd_bound  = std::min(1.0, objective.max_step(z, dz));
        double       alpha      = ccd_bound;
        const double decrease   = g.dot(dz);
        const bool   use_armijo = !kinematic_pending;
        const double round_off  = energy_round_off(e0);
        const double gradient_norm = free_norm(g, free_index);
        Eigen::VectorXd trial, trial_gradient(n);
        double          trial_energy = e0;
        bool            judged_by_gradient = false;
        // A step below the round-off of the positions changes nothing: judged by the
        // gradient, it was once "accepted" 170 times in a row at alpha ~2e-9 (the gradient's
        // own round-off decided), until the iteration limit.
        const double position_round_off = 4 * std::numeric_limits<double>::epsilon() * z.lpNorm<Eigen::Infinity>();
        const auto   stalled = [&](const double a) {
          return a < settings.min_step || a * result.last_step_norm < position_round_off;
        };
        for (;; alpha *= 0.5)
          {
            ++result.line_search_trials;
            if (stalled(alpha))
              {
                // Projected steps that cannot move z: the projected Hessian's direction is not
                // a descent direction that the energy or the gradient can resolve; the exact
                // Hessian gets a try from the same z.
                if (adaptive && !exact && !kinematic_pending)
                  break;
                // A converged-looking but tiny step near machine precision counts as done.
                if (settings.round_off_stall_converges && !kinematic_pending &&
                    std::abs(decrease) <= 1e-12 * std::max(1.0, std::abs(e0)))
                  {
                    result.status = NewtonStatus::converged;
                    return result;
                  }
                if (exact && settings.projection == HessianProjection::adaptive)
                  break;  // projected Newton for the rest of the solve, from the same z
                result.status  = NewtonStatus::line_search_failed;
                result.failure = "line search failed (step below " + std::to_string(settings.min_step) +
                                 " of the Newton step or below the positions' round-off)";
                return result;
              }
            trial              = z + alpha * dz;
            const double e     = objective.value(trial);
            trial_energy       = e;
            judged_by_gradient = false;
            if (!std::isfinite(e))
              continue;
            if (!use_armijo)
              break;
            if (!settings.judge_by_gradient || -alpha * decrease > round_off)
              {
                if (e <= e0 + settings.armijo * alpha * decrease)
                  break;
                continue;
              }
            // The energy cannot resolve this step: an Armijo test on it passes or fails by
            // round-off, which once stalled Newton on "accepted" steps of 1e-6 that changed
            // nothing. The gradient, far from round-off, still tells progress.
            judged_by_gradient = true;
            trial_gradient.setZero();
            objective.gradient(trial, trial_gradient);
            if (free_norm(trial_gradient, free_index) < gradient_norm)
              break;
          }
        if (stalled(alpha))
          {
            // Stalled: projected -> exact, or exact -> projected for the rest of the solve.
            adaptive = !exact;
            exact    = !exact;
            continue;
          }
        z = trial;
        // Kinematic entries that reached their target are snapped exactly.
        if (alpha == 1.0)
          for (Eigen::Index i = 0; i < n; ++i)
            if (kinematic[i])
              z[i] = targets[i];
        objective.accept(z);
        if (settings.monitor)
          settings.monitor({result.iterations, e0, trial_energy - e0, decrease, result.last_step_norm,
                            gradient_norm, ccd_bound, alpha, kinematic_pending, judged_by_gradient, shift, exact},
                           z);
        // Full steps whose length does not shrink: the projected Hessian is a poor model of the
        // energy here and Newton has become linear; the exact Hessian restores quadratic steps.
        if (adaptive && !exact)
          {
            const bool full_step = !kinematic_pending && alpha == 1.0;
            crawling = full_step && result.last_step_norm > 0.5 * last_full_step ? crawling + 1 : 0;
            last_full_step = full_step ? result.last_step_norm : std::numeric_limits<double>::infinity();
            exact = crawling >= settings.crawl_iterations;
          }
      }
    result.status  = NewtonStatus::iteration_limit;
    result.failure = "no convergence in " + std::to_string(settings.max_iterations) + " Newton iterations";
    return result;
  }

  unsigned int NewtonSolver::n_symbolic_analyses() const
  {
    return cholesky_.n_symbolic_analyses() + (distributed_ ? distributed_->n_symbolic_analyses() : 0);
  }

  unsigned int NewtonSolver::n_factorizations() const
  {
    return cholesky_.n_factorizations() + (distributed_ ? distributed_->n_factorizations() : 0);
  }
} // namespace ritr
