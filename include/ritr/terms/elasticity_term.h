#pragma once
// Elasticity, w sum_T |T(u)| Psi(F(x, u)) with w = h^2 in dynamics and 1 in statics (paper
// eq. 6). Derivatives in x take a fast path: the density's derivatives in F (first Piola
// stress, closed-form neo-Hookean Hessian) mapped by the constant P1 shape gradients; the
// joint derivatives in (x, u) of the outer solve use second-order dual numbers on the same
// kernel, and its gradient in u alone is in closed form.
#include <ritr/elasticity/cell_materials.h>
#include <ritr/elasticity/density_hessian.h>
#include <ritr/terms/energy_term.h>

namespace ritr
{
  template <int dim>
  class ElasticityTerm : public EnergyTerm<dim>
  {
  public:
    explicit ElasticityTerm(const CellMaterials<dim> &materials) : materials_(materials) {}

    void   begin_step(const StepContext<dim> &context) override { weight_ = context.potential_weight(); }
    const char *name() const override { return "elasticity"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    void   add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const override;
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;
    // Closed form: the Eshelby stress Psi I - F^T P against the shape gradients.
    void   add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const override;

  private:
    static constexpr int cell_dofs = MatrixAssembly<dim>::cell_dofs;
    // A cell's Hessian in x as d2Psi/dF2 (which the projection acts on) mapped by dF/dx.
    struct CellHessian
    {
      SmallMatrix<dim, double>                    F;
      DensityHessian<dim>                         density_hessian;
      Eigen::Matrix<double, dim * dim, cell_dofs> dF_dx;
      double                                      scale;  // weight times cell measure
      Eigen::Matrix<double, cell_dofs, cell_dofs> element_matrix(const DensityHessian<dim> &m) const
      {
        return scale * dF_dx.transpose() * m * dF_dx;
      }
    };
    CellHessian cell_hessian(const TermPoint &p, std::size_t cell) const;

    const CellMaterials<dim> &materials_;
    double                    weight_ = 1.0;
  };
} // namespace ritr
