#pragma once
// The reference measure barrier of r-ITR (paper eq. 21): kappa_w sum_T b(w_T(u)) with
// b(w) = -(w - w_hat)^2 ln(w / w_hat) below w_hat, which keeps every reference cell from
// collapsing or inverting. w_hat is a tenth of the smallest initial cell measure; the
// stiffness is set per step by the r-ITR solver (the contact barrier's, as in the paper). It
// depends on u alone, so it enters R but not the inner solve's E.
#include <ritr/terms/energy_term.h>

namespace ritr
{
  // sum_t kappa b(w_t(u)) (+infinity for w <= 0). With `project_psd` each cell's Hessian block
  // is projected to be positive semi-definite (as the outer Hessians take it).
  template <int dim>
  double reference_measure_barrier(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &u, double w_hat, double kappa,
                                   Eigen::VectorXd *gradient = nullptr, Triplets *hessian = nullptr,
                                   bool project_psd = true);

  template <int dim>
  class MeasureBarrierTerm : public EnergyTerm<dim>
  {
  public:
    explicit MeasureBarrierTerm(const SimplexMesh<dim> &mesh);

    void   set_stiffness(double kappa) { kappa_ = kappa; }
    double stiffness() const { return kappa_; }
    double threshold() const { return w_hat_; }

    bool   depends_on_state() const override { return false; }
    const char *name() const override { return "measure barrier"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &, Eigen::VectorXd &) const override {}
    void   add_hessian(const TermPoint &, bool, MatrixAssembly<dim> &) const override {}
    bool   convex_in_state() const override { return true; }  // a constant of the state
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    const SimplexMesh<dim> &mesh_;
    double                  w_hat_ = 0, kappa_ = 0;
  };
} // namespace ritr
