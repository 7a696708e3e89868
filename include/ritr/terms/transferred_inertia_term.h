#pragma once
// The inertia of r-ITR with the predictor L2-projected onto every candidate mesh (paper eqs.
// 6, 10, 20):
//
//   K = 1/2 x^T M(u) x - rho x^T (A_t(u) (x) I) x_pred     [+ 1/2 rho pi^T Mbar(u) pi],
//
// A_t the transfer matrix between the start-of-step mesh and the candidate u, x_pred the
// predictor on the start-of-step mesh, and for the uncorrected ablation (eq. 8) the extra
// term of the projected predictor pi = pi_t(x_pred, u). The transfer's quadrature is located
// once per candidate (set_reference), where the x-linear part -rho A_t(u) x_pred is formed
// too, so that the inner solve on that mesh sees a linear term. One density for all bodies.
#include <ritr/terms/inertia_term.h>
#include <ritr/transfer/transfer_operator.h>

namespace ritr
{
  template <int dim>
  class TransferredInertiaTerm : public EnergyTerm<dim>
  {
  public:
    // Throws std::invalid_argument unless every cell has the same density.
    TransferredInertiaTerm(const CellMaterials<dim> &materials, const SimplexQuadrature<dim> &quadrature,
                           InertiaForm form,
                           transfer::TransferIntegration integration = transfer::TransferIntegration::quadrature);

    void   begin_step(const StepContext<dim> &context) override;
    void   set_reference(const Eigen::VectorXd &u) override;
    const char *name() const override { return "inertia"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    bool   convex_in_state() const override { return true; }  // a mass matrix; the transfer is linear in x
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;
    // The transfer's first derivatives only (first-order dual numbers on exact overlaps).
    void   add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const override;

    // Time spent in the transfer (locating, integrating) since construction.
    double transfer_seconds() const { return seconds_; }
    // The transfer from the step's start mesh to the last reference set (dynamics only).
    const transfer::TransferOperator<dim> &transfer() const { return transfer_; }

  private:
    bool adds_projected_predictor() const { return form_ == InertiaForm::uncorrected; }
    // Appends g_up M^-1 g_pu, the part of the uncorrected term's u-Hessian that comes from
    // the projected predictor following the mesh (dense).
    void add_projection_response(const ReferenceDerivativeAssembly<dim> &kinetic, Triplets &huu) const;

    InertiaTerm<dim>                 mass_;  // 1/2 x^T M(u) x
    transfer::TransferOperator<dim>  transfer_;
    InertiaForm                      form_;
    double                           density_ = 0;
    bool                             active_  = true;  // dynamics
    Eigen::VectorXd                  predictor_;        // x_t + h v_t on the start-of-step mesh
    Eigen::VectorXd                  linear_;           // -rho A_t(u) x_pred, the x-linear part
    Eigen::VectorXd                  projected_;        // pi_t(x_pred, u) (uncorrected only)
    double                           constant_ = 0;     // 1/2 rho pi^T Mbar pi (uncorrected only)
    mutable double                   seconds_  = 0;
  };
} // namespace ritr
