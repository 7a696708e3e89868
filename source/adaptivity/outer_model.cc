#include <ritr/adaptivity/outer_model.h>
#include <ritr/solver/steihaug_cg.h>

#include <algorithm>
#include <cmath>

namespace ritr
{
  namespace
  {
    // At most this many Newton iterations of the model per proposal: each costs a CG on S,
    // far less than the trial's inner solve.
    constexpr int max_model_iterations = 8;
  } // namespace

  template <int dim>
  OuterModel<dim>::OuterModel(const OuterCurvature &hessian, const Eigen::VectorXd &g,
                              const Eigen::SparseMatrix<double> &basis)
    : hessian_(hessian)
    , g_(g)
    , basis_(basis)
  {
    sigma_ = std::max(std::abs(g.dot(hessian.apply(g))) / std::max(g.squaredNorm(), 1e-300), 1e-300);
  }

  template <int dim>
  Eigen::SparseMatrix<double> OuterModel<dim>::metric(const Eigen::SparseMatrix<double> &barrier_hessian) const
  {
    Eigen::SparseMatrix<double> identity(g_.size(), g_.size());
    identity.setIdentity();
    return barrier_hessian + sigma_ * identity;
  }

  template <int dim>
  double OuterModel<dim>::length(const Eigen::VectorXd &p) const
  {
    return std::sqrt(p.dot(metric_ * p) / sigma_);
  }

  template <int dim>
  typename OuterModel<dim>::Step OuterModel<dim>::propose(const double radius, const double forcing,
                                                          const double epsilon_r, const StepFilter &step_filter,
                                                          MeasureBarrierModel<dim> &barrier)
  {
    const auto &base = barrier.at_point();
    // The region's norm, with the secants that earlier proposals added; fixed while p grows.
    metric_ = metric(base.hessian + barrier.secants());
    const double   region = std::sqrt(sigma_) * radius;  // in the norm of metric_
    const unsigned max_cg = std::max<Eigen::Index>(g_.size(), 1);
    const LinearMap precondition = [&](const Eigen::VectorXd &v) { return preconditioner_.solve(v); };
    // The rest of R (all but the barrier): its gradient at u and its Hessian.
    const Eigen::VectorXd g_rest     = g_ - base.gradient;
    const auto            apply_rest = [&](const Eigen::VectorXd &d) {
      return Eigen::VectorXd(hessian_.apply(d) - base.hessian * d);
    };
    Eigen::VectorXd p = Eigen::VectorXd::Zero(g_.size()), rest_p = p;  // rest_p: the rest's Hessian times p
    auto            at_p = base;
    // CG from p on the model's Hessian there, S plus the barrier's change of Hessian from u to
    // p and the secants (one sparse matrix, so that a CG product is S's and one sparse
    // product); the preconditioner is refactorised whenever either changes.
    Eigen::SparseMatrix<double> barrier_correction;
    const auto                  refactorize = [&]() {
      const Eigen::SparseMatrix<double> barrier_hessian = at_p.hessian + barrier.secants();
      preconditioner_.factorize(sigma_, barrier_hessian);
      barrier_correction = barrier_hessian - base.hessian;
    };
    // CG from zero, or from a guess: then it solves for the correction to the guess, when the
    // guess's residual is below the gradient's (after a step cut to a fraction, the rest of the
    // direction is most of the next one). The result's step is the guess plus the correction;
    // `interior` is the correction's (the only other field read here).
    const auto newton_direction = [&](const Eigen::VectorXd &model_gradient, const double tolerance,
                                      const Eigen::VectorXd &guess = Eigen::VectorXd()) {
      const LinearMap apply = [&](const Eigen::VectorXd &v) {
        return Eigen::VectorXd(hessian_.apply(v) + barrier_correction * v);
      };
      if (guess.size() > 0)
        {
          const Eigen::VectorXd residual = model_gradient + apply(guess);
          if (residual.norm() < model_gradient.norm())
            {
              SteihaugResult correction = steihaug_cg(apply, residual, region, tolerance, max_cg, precondition);
              correction.step += guess;
              return correction;
            }
        }
      return steihaug_cg(apply, model_gradient, region, tolerance, max_cg, precondition);
    };

    Step           step;
    Eigen::VectorXd model_gradient = g_;
    refactorize();
    SteihaugResult cg = newton_direction(model_gradient, forcing * g_.norm());
    if (cg.interior && (basis_ * cg.step).template lpNorm<Eigen::Infinity>() <= epsilon_r)
      {
        cg      = newton_direction(model_gradient, 1e-8 * g_.norm());
        step.du = basis_ * cg.step;
        if (cg.interior && step.du.template lpNorm<Eigen::Infinity>() <= epsilon_r)
          {
            step.p      = cg.step;
            step.newton = step.converged = true;
            return step;
          }
      }
    for (int k = 0, refinements = 0; k < max_model_iterations;)
      {
        const Eigen::VectorXd d = cg.step;
        // The step's largest fraction inside the region, |p + a d|_M <= region, and admissible.
        const Eigen::VectorXd md = metric_ * d;
        const double pMp = p.dot(metric_ * p), pMd = p.dot(md), dMd = std::max(d.dot(md), 1e-300);
        const double to_boundary = fraction_to_boundary(pMp, pMd, dMd, region);
        const double          alpha_max = std::min({1.0, to_boundary, step_filter(basis_ * p, basis_ * d)});
        const Eigen::VectorXd rest_d    = apply_rest(d);
        const auto [alpha, change] = barrier.best_fraction(p, d, at_p.value, alpha_max, (g_rest + rest_p).dot(d),
                                                           d.dot(rest_d));
        // Cut to less than half by the barrier: the cells it drove in get secants and CG
        // runs again from p.
        if (alpha < 0.5 * alpha_max && refinements < 3 && barrier.add_secants(p, alpha_max * d))
          {
            ++refinements;
            refactorize();
            cg = newton_direction(model_gradient, forcing * g_.norm(), Eigen::VectorXd(alpha * d));
            continue;
          }
        ++k;
        if (!(change < 0))
          break;  // no decrease along d: p is the model's best
        p += alpha * d;
        rest_p += alpha * rest_d;
        step.predicted += change;
        at_p           = barrier.at(p);
        model_gradient = g_rest + rest_p + at_p.gradient;
        // Inside the region with a small model gradient: a Newton step of R.
        const bool on_boundary = alpha >= to_boundary * (1 - 1e-12);
        step.newton            = !on_boundary && model_gradient.norm() <= forcing * g_.norm();
        if (step.newton || on_boundary || change > -1e-3 * std::abs(step.predicted))
          break;
        // The next Newton step of the model, from p; the region's norm stays that of u, so
        // CG's own region is a bound, cut to it above.
        refactorize();
        cg = newton_direction(model_gradient, forcing * g_.norm(), Eigen::VectorXd((1 - alpha) * d));
      }
    step.p  = p;
    step.du = basis_ * p;
    return step;
  }

  template class OuterModel<1>;
  template class OuterModel<2>;
  template class OuterModel<3>;
} // namespace ritr
