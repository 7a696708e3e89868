#include <ritr/common/second_order_dual.h>
#include <ritr/elasticity/density_hessian.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <cmath>

namespace ritr
{
  namespace
  {
    template <int dim>
    using Square = Eigen::Matrix<double, dim, dim>;
    constexpr int n_pairs(const int dim) { return dim * (dim - 1) / 2; }

    // Psi's curvature in the signed singular values s: d2Psi/ds2 and the twist and flip
    // eigenvalues of each pair i < j (in the order (0,1), (0,2), (1,2)).
    template <int dim>
    struct SingularValueCurvature
    {
      Square<dim>                   hessian;
      std::array<double, n_pairs(dim)> twist, flip;
    };

    template <int dim>
    SingularValueCurvature<dim> singular_value_curvature(const Material &m, const Eigen::Matrix<double, dim, 1> &s)
    {
      const double               mu = m.mu(dim), lambda = m.lambda(dim);
      SingularValueCurvature<dim> c;
      int                        pair = 0;
      if (m.model == MaterialModel::neo_hookean)
        {
          // Psi = mu/2 (|s|^2 - dim) - mu ln J + lambda/2 ln^2 J, J = prod s; with
          // k = mu - lambda ln J: Psi_i = mu s_i - k / s_i.
          const double k = mu - lambda * std::log(s.prod());
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j)
              c.hessian(i, j) = i == j ? mu + (k + lambda) / (s[i] * s[i]) : lambda / (s[i] * s[j]);
          for (int i = 0; i < dim; ++i)
            for (int j = i + 1; j < dim; ++j, ++pair)
              {
                c.twist[pair] = mu - k / (s[i] * s[j]);
                c.flip[pair]  = mu + k / (s[i] * s[j]);
              }
          return c;
        }
      // St. Venant-Kirchhoff: Psi = mu sum E_i^2 + lambda/2 (tr E)^2, E_i = (s_i^2 - 1)/2;
      // Psi_i = s_i (2 mu E_i + lambda tr E).
      Eigen::Matrix<double, dim, 1> e = 0.5 * (s.array().square() - 1.0).matrix();
      const double                  trace = e.sum();
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          c.hessian(i, j) = i == j ? 2 * mu * e[i] + lambda * trace + (2 * mu + lambda) * s[i] * s[i] : lambda * s[i] * s[j];
      for (int i = 0; i < dim; ++i)
        for (int j = i + 1; j < dim; ++j, ++pair)
          {
            c.twist[pair] = mu * (s[i] * s[i] - s[i] * s[j] + s[j] * s[j] - 1) + lambda * trace;
            c.flip[pair]  = mu * (s[i] * s[i] + s[i] * s[j] + s[j] * s[j] - 1) + lambda * trace;
          }
      return c;
    }
  } // namespace

  template <int dim>
  DensityHessian<dim> energy_density_hessian(const Material &m, const SmallMatrix<dim, double> &F)
  {
    if (m.model != MaterialModel::neo_hookean)
      {
        SmallMatrix<dim, SecondOrderDual<dim * dim>> f;
        for (int k = 0; k < dim; ++k)
          for (int j = 0; j < dim; ++j)
            f[k][j] = SecondOrderDual<dim * dim>::variable(k * dim + j, F[k][j]);
        return strain_energy_density<dim, SecondOrderDual<dim * dim>>(m, f).hess;
      }
    // H_(ij)(kl) = mu d_ik d_jl + lambda Finv_ji Finv_lk + (mu - lambda ln J) Finv_jk Finv_li
    // (dual numbers would cost as much as the rest of an element's Hessian).
    const double        mu = m.mu(dim), lambda = m.lambda(dim);
    const auto          f_inv     = inverse<dim, double>(F);
    const double        curvature = mu - lambda * std::log(determinant<dim, double>(F));
    DensityHessian<dim> h;
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        for (int k = 0; k < dim; ++k)
          for (int l = 0; l < dim; ++l)
            h(i * dim + j, k * dim + l) = (i == k && j == l ? mu : 0.0) + lambda * f_inv[j][i] * f_inv[l][k] +
                                          curvature * f_inv[j][k] * f_inv[l][i];
    return h;
  }

  template <int dim>
  std::optional<DensityHessian<dim>> density_hessian_projection(const Material &m, const SmallMatrix<dim, double> &F,
                                                                const DensityHessian<dim> &hessian)
  {
    // Linear elasticity is convex; a successful Cholesky factorization proves definiteness.
    if (m.model == MaterialModel::linear || Eigen::LLT<DensityHessian<dim>>(hessian).info() == Eigen::Success)
      return std::nullopt;
    if constexpr (dim == 1)
      {
        if (hessian(0, 0) >= 0)
          return std::nullopt;
        return DensityHessian<dim>(-hessian);
      }
    else
      {
        if (m.model == MaterialModel::neo_hookean && determinant<dim, double>(F) <= 0)
          return std::nullopt;  // outside the energy's domain (+infinity there)
        // Signed SVD: U and V rotations, the sign of det F on the last singular value.
        Square<dim> f;
        for (int k = 0; k < dim; ++k)
          for (int j = 0; j < dim; ++j)
            f(k, j) = F[k][j];
        const Eigen::JacobiSVD<Square<dim>> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
        Square<dim>                         U = svd.matrixU(), V = svd.matrixV();
        Eigen::Matrix<double, dim, 1>       s = svd.singularValues();
        if (U.determinant() < 0)
          {
            U.col(dim - 1) *= -1;
            s[dim - 1] *= -1;
          }
        if (V.determinant() < 0)
          {
            V.col(dim - 1) *= -1;
            s[dim - 1] *= -1;
          }
        const auto curvature = singular_value_curvature<dim>(m, s);

        // Adds -lambda q q^T for a negative eigenvalue lambda of the mode U D V^T (|D| = 1).
        DensityHessian<dim> change   = DensityHessian<dim>::Zero();
        bool                negative = false;
        const auto          clamp    = [&](const double eigenvalue, const Square<dim> &D) {
          if (eigenvalue >= 0)
            return;
          negative                                         = true;
          const Square<dim>                        mode = U * D * V.transpose();
          Eigen::Matrix<double, dim * dim, 1>      q;
          for (int k = 0; k < dim; ++k)
            for (int j = 0; j < dim; ++j)
              q[k * dim + j] = mode(k, j);
          change.noalias() -= eigenvalue * q * q.transpose();
        };
        Eigen::SelfAdjointEigenSolver<Square<dim>> scaling;
        scaling.computeDirect(curvature.hessian);
        for (int a = 0; a < dim; ++a)
          clamp(scaling.eigenvalues()[a], scaling.eigenvectors().col(a).asDiagonal().toDenseMatrix());
        int pair = 0;
        for (int i = 0; i < dim; ++i)
          for (int j = i + 1; j < dim; ++j, ++pair)
            {
              Square<dim> twist = Square<dim>::Zero(), flip = Square<dim>::Zero();
              twist(i, j) = -M_SQRT1_2;
              twist(j, i) = M_SQRT1_2;
              flip(i, j) = flip(j, i) = M_SQRT1_2;
              clamp(curvature.twist[pair], twist);
              clamp(curvature.flip[pair], flip);
            }
        if (!negative)
          return std::nullopt;
        return change;
      }
  }

#define RITR_INSTANTIATE(dim)                                                                                      \
  template DensityHessian<dim> energy_density_hessian<dim>(const Material &, const SmallMatrix<dim, double> &);    \
  template std::optional<DensityHessian<dim>> density_hessian_projection<dim>(                                     \
    const Material &, const SmallMatrix<dim, double> &, const DensityHessian<dim> &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
