#pragma once
// Inertia with the predictor's nodal values read on the current mesh (paper eq. 10, or eq. 8
// for the ablation), as a fixed mesh has it and as r-ITR has it when the predictor is
// projected only after the optimisation:
//
//   K = 1/2 x^T M(u) x - x^T M(u) x_pred   [+ 1/2 x_pred^T M(u) x_pred, uncorrected],
//
// x_pred = x_t + h v_t, M the consistent mass matrix. Per cell K = |T(u)| q(x) with q a
// quadratic in the cell's positions, so all derivatives are closed-form. Without a predictor
// (Predictor::none) it is the mass part 1/2 x^T M(u) x alone, which the transferred inertia
// (transferred_inertia_term.h) completes. Inactive in statics.
#include <ritr/elasticity/cell_materials.h>
#include <ritr/terms/energy_term.h>
#include <ritr/terms/inertia_form.h>

namespace ritr
{
  template <int dim>
  class InertiaTerm : public EnergyTerm<dim>
  {
  public:
    enum class Predictor
    {
      nodal,  // x_pred's nodal values on the current mesh
      none    // the mass part alone
    };
    InertiaTerm(const CellMaterials<dim> &materials, Predictor predictor, InertiaForm form);

    void   begin_step(const StepContext<dim> &context) override;
    const char *name() const override { return "inertia"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    bool   convex_in_state() const override { return true; }  // the mass matrix is positive definite
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;
    void   add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    const CellMaterials<dim> &materials_;
    Predictor                 predictor_kind_;
    InertiaForm               form_;
    bool                      active_ = true;  // dynamics
    Eigen::VectorXd           predictor_;       // zero for Predictor::none
  };
} // namespace ritr
