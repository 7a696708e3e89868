#pragma once
// A limited-memory BFGS approximation of the outer curvature, built from first derivatives
// alone: each accepted outer step s and the change y of the reduced gradient over it (the
// partial derivative of R in u at the solved state, so no solve is needed) refine
//   B = sigma I + sum_i [ y_i y_i^T / (s_i . y_i) - b_i b_i^T / (s_i . b_i) ],  b_i = B_i s_i,
// with B_i the approximation before pair i (the update unrolled, so that a product costs
// O(m n) for m pairs). Pairs are damped (Powell) so that B stays positive definite where R
// is not convex along s, and the pairs outlive the time step that made them: the mesh's
// curvature changes slowly from one step to the next, and the first iterations of a step
// would otherwise be steepest descent. The part of the curvature the measure barrier adds is
// exact in the model (outer_model.h); `with_barrier` adds its Hessian at the model's point so
// that B is, like the reduced Hessian, the curvature of all of R.
#include <ritr/adaptivity/outer_curvature.h>

#include <Eigen/Sparse>

#include <deque>

namespace ritr
{
  class QuasiNewtonCurvature : public OuterCurvature
  {
  public:
    explicit QuasiNewtonCurvature(unsigned int memory = 8) : memory_(memory) {}

    // Records the step s and the change of gradient y of the part of R it approximates;
    // returns false (and records nothing) when s or y carries no information.
    bool update(const Eigen::VectorXd &s, const Eigen::VectorXd &y);
    bool empty() const { return pairs_.empty(); }
    // The scale of the base, sigma: set by each pair, or here before the first.
    double sigma() const { return sigma_; }
    void   set_scale(const double sigma) { sigma_ = sigma; }

    // The approximation as numbers (sigma, then each pair's s and measured y), and back for
    // vectors of n entries; restore throws std::invalid_argument for numbers it cannot be.
    Eigen::VectorXd state() const;
    void            restore(const Eigen::VectorXd &state, Eigen::Index n);

    // The barrier Hessian the products include (none: an empty matrix).
    void with_barrier(const Eigen::SparseMatrix<double> &barrier_hessian) { barrier_ = barrier_hessian; }

    // B p, plus the barrier's Hessian times p.
    Eigen::VectorXd apply(const Eigen::VectorXd &p) const override;

  private:
    struct Pair
    {
      Eigen::VectorXd s, measured;  // the step and the change of gradient over it
      Eigen::VectorXd y, b;         // y damped; b = B_i s, B_i the approximation before this pair
      double          sy = 0, sb = 0;
    };
    // B p without the barrier.
    Eigen::VectorXd product(const Eigen::VectorXd &p, std::size_t n_pairs) const;
    // b and sb of every pair after sigma or the oldest pair changed.
    void rebuild();

    unsigned int                memory_;
    double                      sigma_ = 0;
    std::deque<Pair>            pairs_;
    Eigen::SparseMatrix<double> barrier_;
  };
} // namespace ritr
