#pragma once
// The one Newton driver: minimise an objective over the free entries of z with a line
// search, while prescribed ("kinematic") entries -- Dirichlet nodes and scripted obstacle
// vertices -- are driven to their targets inside the same line search, so that continuous
// collision detection sees their motion too. Backtracking starts from the largest step the
// objective certifies (CCD, the reference mesh's step filter) and takes the first trial
// that passes Armijo's test; for an implicit step, where the predicted decrease is below the
// energy's round-off, a trial is accepted when it lowers the norm of the free gradient
// instead. The inner solve over the state and the outer line-search solves over the
// reference mesh (adaptivity/line_search_outer.h) both run on it.
#include <ritr/common/thread_pools.h>
#include <ritr/common/triplets.h>
#include <ritr/solver/distributed_linear_system.h>
#include <ritr/solver/hessian_projection.h>
#include <ritr/solver/reduced_system.h>
#include <ritr/solver/sparse_cholesky.h>

#include <Eigen/Sparse>

#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ritr
{
  // The objective as the solver sees it.
  class NewtonObjective
  {
  public:
    virtual ~NewtonObjective() = default;
    // Called once per iteration before derivatives (active contact set, barrier stiffness).
    virtual void begin_iteration(const Eigen::VectorXd &z) { (void)z; }
    virtual double value(const Eigen::VectorXd &z) = 0;  // +infinity when inadmissible
    virtual void   gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g) = 0;
    // With `project`, every element and contact stencil is projected onto the positive
    // semi-definite cone; without, the exact Hessian (possibly indefinite).
    virtual void   hessian(const Eigen::VectorXd &z, Triplets &h, bool project) = 0;
    // The exact Hessian appended to h, and the changes that make the appended triplets the
    // projected Hessian's appended to `projection` (the trust-region iteration needs both).
    // The default assembles twice and requires the two lists to have the same structure;
    // objectives override it to evaluate each stencil once.
    virtual void hessian_and_projection(const Eigen::VectorXd &z, Triplets &h, TripletChanges &projection)
    {
      const std::size_t first = h.size();
      hessian(z, h, false);
      Triplets projected;
      hessian(z, projected, true);
      if (projected.size() != h.size() - first)
        throw std::logic_error("hessian_and_projection: the projected Hessian has another structure");
      for (std::size_t i = 0; i < projected.size(); ++i)
        {
          const auto &exact = h[first + i];
          if (projected[i].row() != exact.row() || projected[i].col() != exact.col())
            throw std::logic_error("hessian_and_projection: the projected Hessian has another structure");
          if (projected[i].value() != exact.value())
            projection.emplace_back(first + i, projected[i].value() - exact.value());
        }
    }
    // Largest fraction of dz that is certified admissible (intersection-free; 1 without
    // contact).
    virtual double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz)
    {
      (void)z;
      (void)dz;
      return 1.0;
    }
    // The Newton step as the objective trusts it (default: as solved); the outer solve over
    // the reference mesh caps its length.
    virtual void limit_step(const Eigen::VectorXd &z, Eigen::VectorXd &dz) const
    {
      (void)z;
      (void)dz;
    }
    // The length of a step that the tolerance is compared with (default |dz|_inf).
    virtual double step_norm(const Eigen::VectorXd &dz) const { return dz.lpNorm<Eigen::Infinity>(); }
    // Called with the new iterate after every accepted step (an objective whose evaluations
    // solve for more than z keeps the state of the accepted trial).
    virtual void accept(const Eigen::VectorXd &z) { (void)z; }
  };

  // What decided one Newton iteration (a row of newton.csv with Solver/newton log).
  struct NewtonIterationRecord
  {
    unsigned int iteration          = 0;
    double       energy             = 0;  // at the start of the iteration
    double       energy_change      = 0;  // over the accepted step
    double       predicted_decrease = 0;  // g.dz over the full step (negative: descent)
    double       step_norm          = 0;  // |dz|_inf
    double       gradient_norm      = 0;  // |g|_2 over the free entries
    double       ccd_bound          = 1;  // largest intersection-free fraction of dz
    double       alpha              = 1;  // accepted fraction
    bool         prescribed_moving  = false;  // kinematic entries not yet at their targets
    bool         judged_by_gradient = false;  // step below the energy's round-off
    double       hessian_shift      = 0;  // multiple of the identity added to make it definite
    bool         exact_hessian      = false;  // the step solved with the exact Hessian
    // Trust region only: the region's radius (projected-Hessian norm) the step was taken in,
    // and the CG iterations of its last solve (0 for line-search steps).
    double       trust_radius       = 0;
    unsigned int cg_iterations      = 0;
  };

  // The tolerance and the iteration limit come from the caller (the scene's Solver section
  // for the implicit step, its Adaptivity section for the outer solves); the rest are the
  // algorithm's constants.
  struct NewtonSettings
  {
    double       tolerance      = 0;  // on the step norm (NewtonObjective::step_norm)
    unsigned int max_iterations = 0;
    double       armijo         = 1e-4;
    double       min_step       = 1e-12;  // backtracking gives up below this fraction
    // Where the predicted decrease is below the energy's round-off, judge a trial by the
    // norm of the free gradient (an implicit step); off: Armijo's test on the value alone.
    bool         judge_by_gradient = true;
    // A line search that stalls while the full step's predicted decrease is below 1e-12 of
    // the value counts as converged (round-off); off: it is reported as a failed search.
    bool         round_off_stall_converges = true;
    HessianProjection projection = HessianProjection::always;
    unsigned int crawl_iterations = 5;  // adaptive: full, non-shrinking steps before switching
    // Adaptive: start with the exact Hessian (a start close to the solution, where projected
    // Newton only crawls); a failed exact line search still falls back to projected steps.
    bool         start_exact = false;
    // Trust region, one process: a factorization of at least this many flops goes on
    // preconditioning the solve's next iterations for as long as CG converges in a few
    // iterations with it; infinity: one factorization per iteration. The default reuses those
    // of 3D meshes from about 40K vertices, where a back-substitution costs about 1/100 of a
    // factorization in wall time (doc/method.md).
    double       reuse_factorizations_from = large_factorization_flops;
    // Called after every accepted step with the new iterate (empty: no log).
    std::function<void(const NewtonIterationRecord &, const Eigen::VectorXd &z)> monitor;
    // A run shared among processes (null or one process: serial, CHOLMOD): the objective's
    // values and gradients are whole, its Hessian this process's part, and the Newton system
    // is solved by Trilinos (HessianProjection::always, or trust_region with the direct solver).
    const WorkShare  *work_share        = nullptr;
    DistributedSolver distributed_solver = DistributedSolver::direct;
  };

  enum class NewtonStatus
  {
    converged,           // step below the tolerance
    line_search_failed,  // no trial down to the smallest step was accepted
    iteration_limit,
    not_finite           // the objective is not finite at an iterate
  };

  struct NewtonResult
  {
    NewtonStatus status             = NewtonStatus::iteration_limit;
    unsigned int iterations         = 0;
    unsigned int line_search_trials = 0;
    double       energy             = 0;
    double       last_step_norm     = 0;
    std::string  failure;  // why it did not converge
    bool         converged() const { return status == NewtonStatus::converged; }
  };

  class NewtonSolver
  {
  public:
    // `kinematic[i]` marks prescribed entries; `targets` holds their values at the end of
    // the step (entries of free unknowns are ignored).
    NewtonResult minimize(NewtonObjective &objective, Eigen::VectorXd &z,
                          const std::vector<bool> &kinematic, const Eigen::VectorXd &targets,
                          const NewtonSettings &settings);

    const SparseCholesky &linear_solver() const { return cholesky_; }
    double seconds_in_linear_solves() const { return linear_seconds_; }
    // Symbolic analyses (new patterns) and numeric factorizations, of whichever linear
    // solver the solves used.
    unsigned int n_symbolic_analyses() const;
    unsigned int n_factorizations() const;

  private:
    // What a trust-region solve carries from one iteration to the next.
    struct TrustRegion
    {
      double       radius         = 0;  // in the norm of the preconditioner; 0: not started
      double       first_gradient = 0;
      unsigned int cg_iterations  = 0;  // of the last iteration's accepted step
    };
    enum class Outcome
    {
      accepted,
      converged,
      failed
    };
    // One iteration of HessianProjection::trust_region at z, all prescribed entries at their
    // targets (newton_trust_region.cc). The exact Hessian is assembled in exact_system_, the
    // projected one in system_ and factorized (with `shift`); `g` is the full gradient at z,
    // e0 the energy there.
    Outcome trust_region_iteration(NewtonObjective &objective, Eigen::VectorXd &z, const Eigen::VectorXd &g,
                                   const std::vector<int> &free_index, double e0, double shift,
                                   const NewtonSettings &settings, TrustRegion &region, NewtonResult &result);

    ReducedSystem  system_;  // keeps its pattern across iterations and solves
    ReducedSystem  exact_system_;  // the exact Hessian of a trust-region iteration
    Triplets       exact_triplets_;  // its entries, kept so that their storage is reused
    TripletChanges projection_changes_;  // exact_triplets_ to the projected Hessian's
    SparseCholesky cholesky_;
    std::unique_ptr<DistributedLinearSystem> distributed_;  // a run shared among processes
    double         linear_seconds_ = 0;
  };
} // namespace ritr
