#pragma once
// The r-ITR objective of one time step and its derivatives in the reference positions u
// (paper eqs. 6, 10, 14, 19-21):
//
//   R(z, u) = 1/2 x^T M(u) x - rho x^T (A_t(u) (x) I) x_pred          (corrected inertia)
//             + w_p (Psi(x, u) - gravity work) + kappa B(z, u) + D(z, u)
//             + kappa_w sum_t b(w_t(u))                             (reference measure barrier)
//
// z = [body nodes x, obstacle vertices]. The ablations of the paper change single terms:
//  - uncorrected inertia adds 1/2 rho pi^T Mbar(u) pi with pi = pi_t(x_pred, u) (eq. 8);
//  - projection after optimisation replaces A_t(u) x_pred by Mbar(u) x_pred (the
//    predictor's nodal values read on the new mesh, remapped only once the step is done);
//  - statics drops inertia and transfer altogether.
#include <ritr/adaptivity/reference_penalties.h>
#include <ritr/contact/contact_potential.h>
#include <ritr/scene/adaptivity_options.h>
#include <ritr/elasticity/bulk_energy.h>
#include <ritr/step/step_context.h>
#include <ritr/transfer/transfer_operator.h>

namespace ritr
{
  template <int dim>
  class RitrObjective
  {
  public:
    // `bulk` carries the materials (one density) and is shared with the inner solve.
    RitrObjective(const SimplexMesh<dim> &mesh, BulkEnergy<dim> &bulk, ContactPotential<dim> *contact,
                  const SimplexQuadrature<dim> &quadrature, InertiaForm inertia,
                  PredictorProjection projection);

    // Start of a step: the start-of-step mesh u_t and the predictor x_t + h v_t on it. Sets
    // the bulk weights (dynamic: inertia 1, potential h^2; statics: 0 and 1).
    void begin_step(const StepContext<dim> &step);

    // The candidate mesh u of the following evaluations (locates the transfer quadrature).
    void set_candidate(const Eigen::VectorXd &u);
    // The x-linear part of the inertia on the candidate, -rho A_t(u) x_pred, as l in l^T x
    // (empty when the bulk term holds the predictor itself).
    Eigen::VectorXd linear_term() const;
    // The measure barrier's stiffness kappa_w and threshold w_hat (0 stiffness: no barrier).
    void set_measure_barrier(double kappa, double w_hat) { kappa_w_ = kappa, w_hat_ = w_hat; }

    // R(z, u) on the candidate set last; +infinity when inadmissible.
    double value(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const;

    // Derivatives at (z, u). g_u and H_uu always, H_uu per `block` (bulk_energy.h; the
    // measure barrier, which has no x, adds per-cell PSD blocks); with `coupling` also g_x
    // and the x-x and x-u Hessian blocks (rows in state numbering).
    struct Derivatives
    {
      Eigen::VectorXd gu, gx;
      Triplets        huu, hxx, hxu;
    };
    Derivatives derivatives(const Eigen::VectorXd &z, const Eigen::VectorXd &u, ReferenceBlock block,
                            bool coupling) const;

    // pi_t(y, u) for a start-of-step field y (the velocity update).
    Eigen::VectorXd project(const Eigen::VectorXd &y, const Eigen::VectorXd &u);
    double          transfer_seconds() const { return transfer_seconds_; }

  private:
    // Appends g_up M^-1 g_pu, the part of the uncorrected inertia's u-Hessian that comes from
    // the projected predictor following the mesh (see derivatives()).
    void add_projection_response(const typename BulkEnergy<dim>::JointDerivatives &kinetic, Eigen::Index n_u,
                                 Triplets &huu) const;
    bool uses_transfer() const { return dynamic_ && projection_ == PredictorProjection::in_optimization; }
    bool adds_projected_predictor() const { return uses_transfer() && inertia_ == InertiaForm::uncorrected; }

    const SimplexMesh<dim>         &mesh_;
    BulkEnergy<dim>                &bulk_;
    BulkEnergy<dim>                 mass_;  // 1/2 x^T M(u) x alone (uncorrected inertia)
    ContactPotential<dim>          *contact_;
    transfer::TransferOperator<dim> transfer_;
    InertiaForm                     inertia_;
    PredictorProjection             projection_;
    double                          density_ = 0;
    bool                            dynamic_ = true;
    Eigen::VectorXd                 predictor_;  // x_t + h v_t on the start-of-step mesh
    Eigen::VectorXd                 projected_predictor_;  // pi_t(x_pred, u) on the candidate
    double                          kappa_w_ = 0, w_hat_ = 0;
    mutable double                  transfer_seconds_ = 0;
  };
} // namespace ritr
