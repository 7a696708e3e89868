#pragma once
// One time step of optimal r-adaptive in-timestep remeshing (paper Algorithm 1): a truncated
// Newton method over the reference positions u, with the implicit step x = argmin E(., u)
// solved inside every evaluation.
//
//   R(x, u) = 1/2 rho x^T Mbar(u) x - rho x^T (A_t(u) (x) I) x_pred + h^2 (Psi(x, u) - gravity work)
//             + sliding penalties(u) + reference measure barrier(u)
//
// with the in-optimization L2 transfer A_t of the predictor from the start-of-step mesh
// (eqs. 6, 10, 19) and the velocity update v = (x - pi_t(x^t, u)) / h. This first version
// covers contact-free dynamics of single-density bodies; contact and friction (whose weights
// already have u-derivatives) are wired in next.
#include <ritr/adaptivity/reference_penalties.h>
#include <ritr/elasticity/bulk_energy.h>
#include <ritr/solver/newton.h>
#include <ritr/transfer/transfer_operator.h>

namespace ritr
{
  // The outer Hessian: `truncated` is Proj+(d2R/du2) assembled from per-cell PSD blocks
  // (paper eq. 23); `full` adds the implicit response of x, -H_ux H_xx^{-1} H_xu, as a dense
  // Schur complement projected as a whole (small meshes only: it is dense).
  enum class RitrHessian
  {
    truncated,
    full
  };

  struct RitrSettings
  {
    RitrHessian  hessian               = RitrHessian::truncated;
    double       epsilon_r             = 1e-6;  // stop when |du|_inf <= epsilon_r
    double       epsilon_e             = 1e-8;  // inner Newton: |dx|_inf <= epsilon_e * h
    unsigned int max_outer_iterations  = 200;
    double       sliding_tolerance     = 1e-6;  // eps_b
    // Stiffness of the sliding penalties and of the measure barrier; 0 picks h^2 E, the
    // scale of the elastic term per unit measure.
    double       penalty_stiffness     = 0;
  };

  template <int dim>
  class RitrSolver
  {
  public:
    // `mesh` gives the connectivity, the initial reference (for the sliding anchors and the
    // measure threshold w_hat = 0.1 * smallest initial cell) and the material ids.
    RitrSolver(const SimplexMesh<dim> &mesh, const Material &material, const RitrSettings &settings,
               const transfer::SimplexQuadrature<dim> &quadrature);

    struct Result
    {
      Eigen::VectorXd u, x, v;
      double          objective = 0;
      unsigned int    outer_iterations = 0, inner_iterations = 0, line_search_trials = 0;
    };

    // Advances (u_t, x_t, v_t) by one implicit Euler step of size h.
    Result step(const Eigen::VectorXd &u_t, const Eigen::VectorXd &x_t, const Eigen::VectorXd &v_t, double h,
                const std::array<double, dim> &gravity);

  private:
    // x = argmin_x E(x, u), warm-started from x; returns the Newton iterations.
    unsigned int solve_inner(const Eigen::VectorXd &u, Eigen::VectorXd &x);
    double       penalties(const Eigen::VectorXd &u, Eigen::VectorXd *g, Triplets *h) const;
    // R(x, u); the transfer must have been set to the candidate u.
    double       objective(const Eigen::VectorXd &x, const Eigen::VectorXd &u) const;
    // Largest step fraction in (0, 1] keeping every reference cell above a fifth of its measure.
    double       step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du) const;

    const SimplexMesh<dim>              &mesh_;
    Material                             material_;
    RitrSettings                         settings_;
    BulkEnergy<dim>                      bulk_;
    transfer::TransferOperator<dim>      transfer_;
    std::vector<SlidingConstraint<dim>>  sliding_;
    std::vector<bool>                    u_fixed_;
    double                               w_hat_ = 0;
    NewtonSolver                         newton_;
    Eigen::VectorXd                      predictor_;  // x_pred on the start-of-step mesh
    double                               h_ = 1;
  };
} // namespace ritr
