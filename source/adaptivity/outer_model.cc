#include <ritr/adaptivity/outer_model.h>
#include <ritr/solver/steihaug_cg.h>

#include <cmath>

namespace ritr
{
  template <int dim>
  OuterModel<dim>::OuterModel(const ReducedHessian &hessian, const MeasureBarrierModel<dim> &barrier,
                              const Eigen::VectorXd &g, const Eigen::SparseMatrix<double> &basis,
                              SparseCholesky &preconditioner)
    : hessian_(hessian)
    , g_(g)
    , basis_(basis)
    , preconditioner_(preconditioner)
  {
    sigma_ = std::max(std::abs(g.dot(hessian.apply(g))) / std::max(g.squaredNorm(), 1e-300), 1e-300);
    build_preconditioner(barrier);
  }

  template <int dim>
  void OuterModel<dim>::build_preconditioner(const MeasureBarrierModel<dim> &barrier)
  {
    Eigen::SparseMatrix<double> identity(g_.size(), g_.size());
    identity.setIdentity();
    metric_ = barrier.stiffness() + sigma_ * identity;
    Eigen::SparseMatrix<double> lower = metric_.template triangularView<Eigen::Lower>();
    lower.makeCompressed();
    preconditioner_.factorize(lower);
  }

  template <int dim>
  double OuterModel<dim>::length(const Eigen::VectorXd &p) const
  {
    return std::sqrt(p.dot(metric_ * p) / sigma_);
  }

  template <int dim>
  typename OuterModel<dim>::Step OuterModel<dim>::propose(const double radius, const double forcing,
                                                          const double epsilon_r,
                                                          const std::function<double(const Eigen::VectorXd &)> &step_filter,
                                                          MeasureBarrierModel<dim> &barrier)
  {
    Step step;
    const LinearMap apply = [&](const Eigen::VectorXd &p) {
      return Eigen::VectorXd(hessian_.apply(p) + barrier.apply_secants(p));
    };
    const LinearMap precondition = [&](const Eigen::VectorXd &v) { return preconditioner_.solve(v); };
    const double    region       = std::sqrt(sigma_) * radius;
    const unsigned  max_cg       = std::max<Eigen::Index>(g_.size(), 1);
    for (int refinement = 0;; ++refinement)
      {
        SteihaugResult cg = steihaug_cg(apply, g_, region, forcing * g_.norm(), max_cg, precondition);
        if (cg.interior && (basis_ * cg.step).template lpNorm<Eigen::Infinity>() <= epsilon_r)
          cg = steihaug_cg(apply, g_, region, 1e-8 * g_.norm(), max_cg, precondition);
        step.p      = cg.step;
        step.du     = basis_ * cg.step;
        step.newton = cg.interior;
        step.converged = cg.interior && step.du.template lpNorm<Eigen::Infinity>() <= epsilon_r;
        if (step.converged)
          return step;
        // The model along the step: quadratic for all but the barrier, whose actual change
        // it takes; the best admissible fraction of the step.
        const double alpha_max = step_filter(step.du);
        const double slope     = (g_ - barrier.gradient()).dot(cg.step);
        const double curvature = cg.step.dot(hessian_.apply(cg.step)) - barrier.curvature(cg.step);
        const auto [alpha, predicted] = barrier.best_fraction(cg.step, alpha_max, slope, curvature);
        step.p *= alpha;
        step.du *= alpha;
        step.predicted = predicted;
        if (alpha >= 0.5 * alpha_max || refinement == 3 || !barrier.add_secants(alpha_max * cg.step))
          return step;
        build_preconditioner(barrier);
      }
  }

  template class OuterModel<1>;
  template class OuterModel<2>;
  template class OuterModel<3>;
} // namespace ritr
