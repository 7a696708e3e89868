#pragma once
// Elasticity, w sum_T |T(u)| Psi(F(x, u)) with w = h^2 in dynamics and 1 in statics (paper
// eq. 6). Derivatives in x take a fast path: the density's derivatives in F (first Piola
// stress, closed-form neo-Hookean Hessian) mapped by the constant P1 shape gradients; the
// joint derivatives in (x, u) of the outer solve use second-order dual numbers on the same
// kernel, and its gradient in u alone is in closed form.
#include <ritr/elasticity/cell_materials.h>
#include <ritr/elasticity/density_hessian.h>
#include <ritr/terms/energy_term.h>

#include <array>

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
      SmallMatrix<dim, double>                     F;
      DensityHessian<dim>                          density_hessian;
      std::array<std::array<double, dim>, dim + 1> shape_gradients;  // dN_a/dX_j
      double                                       scale;            // weight times cell measure
      // scale dF/dx^T m dF/dx, with F_kj = sum_a x_ak dN_a/dX_j: only dN_a/dX_j of dF/dx's
      // entries are not zero, so the products run over those (a third of the dense products'
      // arithmetic, which Eigen also sent through its GEMM path).
      Eigen::Matrix<double, cell_dofs, cell_dofs> element_matrix(const DensityHessian<dim> &m) const
      {
        Eigen::Matrix<double, cell_dofs, dim * dim> left;  // scale dF/dx^T m
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            for (int column = 0; column < dim * dim; ++column)
              {
                double sum = 0;
                for (int j = 0; j < dim; ++j)
                  sum += shape_gradients[a][j] * m(k * dim + j, column);
                left(a * dim + k, column) = scale * sum;
              }
        Eigen::Matrix<double, cell_dofs, cell_dofs> result;
        for (int row = 0; row < cell_dofs; ++row)
          for (int b = 0; b <= dim; ++b)
            for (int l = 0; l < dim; ++l)
              {
                double sum = 0;
                for (int j = 0; j < dim; ++j)
                  sum += left(row, l * dim + j) * shape_gradients[b][j];
                result(row, b * dim + l) = sum;
              }
        return result;
      }
    };
    CellHessian cell_hessian(const TermPoint &p, std::size_t cell) const;

    const CellMaterials<dim> &materials_;
    double                    weight_ = 1.0;
  };
} // namespace ritr
