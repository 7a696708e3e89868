#pragma once
// The work of body forces (gravity, load factor applied) against the positions,
// -w sum_T |T(u)| rho/(d+1) sum_a x_a . g with w = h^2 in dynamics, 1 in statics: the lumped
// form of -w x^T f(u) in paper eq. 6, linear in x.
#include <ritr/elasticity/cell_materials.h>
#include <ritr/terms/energy_term.h>

namespace ritr
{
  template <int dim>
  class BodyForceTerm : public EnergyTerm<dim>
  {
  public:
    explicit BodyForceTerm(const CellMaterials<dim> &materials) : materials_(materials) {}

    void   begin_step(const StepContext<dim> &context) override;
    const char *name() const override { return "body force"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &, bool, MatrixAssembly<dim> &) const override {}  // linear in x
    bool   convex_in_state() const override { return true; }
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;
    void   add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    // -w rho / (d + 1) g: the force on each node of a cell per unit cell measure.
    Eigen::Matrix<double, dim, 1> nodal_force_density(unsigned int c) const;

    const CellMaterials<dim> &materials_;
    std::array<double, dim>   gravity_{};
    double                    weight_ = 1.0;
    bool                      any_    = false;  // a non-zero gravity
  };
} // namespace ritr
