#pragma once
// The paper's outer solves over the reference mesh with a line search (section 5.4,
// Algorithm 1), as objectives of the one Newton driver (solver/newton.h) in the sliding
// basis u = u_0 + B p:
//  - NestedOuterObjective: R(x(u), u) with x = argmin E(., u) solved at every trial mesh
//    (physical admissibility) and the truncated, full or filtered outer Hessian;
//  - JointOuterObjective: R(z, u) over the free state and p together, the ablation without
//    physical admissibility (no contact).
// Steps are trusted up to half the initial smallest cell size (the nested solve) and cut by
// the step filter, which keeps every reference cell above a fifth of its measure; a trial is
// taken as soon as R does not rise.
#include <ritr/adaptivity/ritr_options.h>
#include <ritr/solver/newton.h>
#include <ritr/terms/term_sum.h>

#include <Eigen/Sparse>

#include <functional>

namespace ritr
{
  // What both objectives share with the r-ITR solver.
  template <int dim>
  struct OuterSetting
  {
    TermSum<dim>                      &terms;
    const Eigen::SparseMatrix<double> &basis;       // reference entries x sliding directions
    const std::vector<int>            &free_state;  // non-kinematic state entries
    // x = argmin E(., u) warm-started from z; false if the inner solve failed.
    std::function<bool(const Eigen::VectorXd &u, Eigen::VectorXd &z)> solve_on_mesh;
    // The largest admissible fraction in (0, 1] of the reference step du from u.
    std::function<double(const Eigen::VectorXd &u, const Eigen::VectorXd &du)> step_filter;
  };

  // Newton settings for an outer line-search solve: stop when the reference step is below
  // epsilon_r; accept any trial that does not raise R.
  NewtonSettings outer_newton_settings(double epsilon_r, unsigned int max_iterations);

  template <int dim>
  class NestedOuterObjective : public NewtonObjective
  {
  public:
    // Starts at (u0, z0) with R(z0, u0) = r0; `trust` is the longest step (max norm).
    NestedOuterObjective(const OuterSetting<dim> &setting, RitrHessian hessian, double filter_threshold, double trust,
                         const Eigen::VectorXd &u0, const Eigen::VectorXd &z0, double r0);

    void   begin_iteration(const Eigen::VectorXd &p) override;
    double value(const Eigen::VectorXd &p) override;
    void   gradient(const Eigen::VectorXd &p, Eigen::VectorXd &g) override;
    void   hessian(const Eigen::VectorXd &p, Triplets &h, bool project) override;
    void   limit_step(const Eigen::VectorXd &p, Eigen::VectorXd &dp) const override;
    double max_step(const Eigen::VectorXd &p, const Eigen::VectorXd &dp) override;
    double step_norm(const Eigen::VectorXd &dp) const override;
    void   accept(const Eigen::VectorXd &p) override;

    Eigen::VectorXd        reference(const Eigen::VectorXd &p) const { return u0_ + setting_.basis * p; }
    const Eigen::VectorXd &state() const { return z_; }  // at the accepted mesh
    double                 objective() const { return r_; }

  private:
    OuterSetting<dim>                             setting_;
    RitrHessian                                   hessian_kind_;
    double                                        filter_threshold_, trust_;
    Eigen::VectorXd                               u0_, p_, z_;
    double                                        r_;
    Eigen::VectorXd                               trial_p_, trial_z_;
    double                                        trial_r_ = 0;
    typename TermSum<dim>::ReferenceDerivatives   derivatives_;  // at the accepted mesh
  };

  template <int dim>
  class JointOuterObjective : public NewtonObjective
  {
  public:
    // y = [free state entries, basis coordinates]; z0 holds the prescribed entries' targets.
    JointOuterObjective(const OuterSetting<dim> &setting, const Eigen::VectorXd &u0, const Eigen::VectorXd &z0);

    void   begin_iteration(const Eigen::VectorXd &y) override;
    double value(const Eigen::VectorXd &y) override;
    void   gradient(const Eigen::VectorXd &y, Eigen::VectorXd &g) override;
    void   hessian(const Eigen::VectorXd &y, Triplets &h, bool project) override;
    double max_step(const Eigen::VectorXd &y, const Eigen::VectorXd &dy) override;
    double step_norm(const Eigen::VectorXd &dy) const override;

    Eigen::Index    size() const { return n_free() + setting_.basis.cols(); }
    Eigen::VectorXd reference(const Eigen::VectorXd &y) const;
    Eigen::VectorXd state(const Eigen::VectorXd &y) const;

  private:
    Eigen::Index n_free() const { return setting_.free_state.size(); }

    OuterSetting<dim>                           setting_;
    Eigen::VectorXd                             u0_, z0_;
    typename TermSum<dim>::ReferenceDerivatives derivatives_;
  };
} // namespace ritr
