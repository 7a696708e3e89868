#pragma once
// Hyperelastic energy densities Psi(F), written once as templates on the scalar type so that
// their derivatives come from SecondOrderDual (and are checked by finite differences).
#include <ritr/common/enum_names.h>
#include <ritr/common/second_order_dual.h>
#include <ritr/common/small_matrix.h>

#include <cmath>
#include <limits>
#include <string>

namespace ritr
{
  enum class MaterialModel
  {
    neo_hookean,
    linear,
    stvk
  };

  // The one mapping between models and their names in a parameter file.
  inline constexpr EnumNames<MaterialModel, 3> material_model_names{{{MaterialModel::neo_hookean, "neo-hookean"},
                                                                      {MaterialModel::linear, "linear"},
                                                                      {MaterialModel::stvk, "stvk"}}};

  MaterialModel material_model_from(const std::string &name);  // neo-hookean|linear|stvk

  struct Material
  {
    MaterialModel model          = MaterialModel::neo_hookean;
    double        youngs_modulus = 1e5;
    double        poisson_ratio  = 0.3;
    double        density        = 1e3;

    // Lame parameters. 2D is plane strain (the 3D constants); a 1D rod is in uniaxial
    // stress, so its modulus is E whatever the Poisson ratio.
    double mu(const int dim) const
    {
      return dim == 1 ? 0.5 * youngs_modulus : youngs_modulus / (2 * (1 + poisson_ratio));
    }
    double lambda(const int dim) const
    {
      return dim == 1 ? 0.0 :
                        youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
    }
  };

  // Strain energy density per unit reference measure. Neo-Hookean returns +infinity for an
  // inverted element (J <= 0) when evaluated on doubles; callers evaluating derivatives must
  // have checked J > 0 first.
  template <int dim, typename Scalar>
  Scalar strain_energy_density(const Material &m, const SmallMatrix<dim, Scalar> &F)
  {
    const double mu = m.mu(dim), lambda = m.lambda(dim);
    switch (m.model)
      {
        case MaterialModel::neo_hookean:
          {
            const Scalar J = determinant<dim, Scalar>(F);
            if (value_of(J) <= 0.0)
              return Scalar(std::numeric_limits<double>::infinity());
            Scalar trace_c(0.0);
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                trace_c = trace_c + F[i][j] * F[i][j];
            const Scalar log_j = log(J);
            return 0.5 * mu * (trace_c - double(dim)) - mu * log_j + 0.5 * lambda * log_j * log_j;
          }
        case MaterialModel::linear:
          {
            Scalar eps_eps(0.0), trace(0.0);
            for (int i = 0; i < dim; ++i)
              {
                trace = trace + (F[i][i] - 1.0);
                for (int j = 0; j < dim; ++j)
                  {
                    const Scalar e = 0.5 * (F[i][j] + F[j][i]) - (i == j ? 1.0 : 0.0);
                    eps_eps        = eps_eps + e * e;
                  }
              }
            return mu * eps_eps + 0.5 * lambda * trace * trace;
          }
        case MaterialModel::stvk:
        default:
          {
            SmallMatrix<dim, Scalar> E;
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                {
                  Scalar c(0.0);
                  for (int k = 0; k < dim; ++k)
                    c = c + F[k][i] * F[k][j];
                  E[i][j] = 0.5 * (c - (i == j ? 1.0 : 0.0));
                }
            Scalar ee(0.0), trace(0.0);
            for (int i = 0; i < dim; ++i)
              {
                trace = trace + E[i][i];
                for (int j = 0; j < dim; ++j)
                  ee = ee + E[i][j] * E[i][j];
              }
            return mu * ee + 0.5 * lambda * trace * trace;
          }
      }
  }

  // First Piola-Kirchhoff stress P = dPsi/dF on doubles (the gradient fast path; the
  // finite-difference tests check it against strain_energy_density).
  template <int dim>
  SmallMatrix<dim, double> first_piola_stress(const Material &m, const SmallMatrix<dim, double> &F)
  {
    const double             mu = m.mu(dim), lambda = m.lambda(dim);
    SmallMatrix<dim, double> P{};
    switch (m.model)
      {
        case MaterialModel::neo_hookean:
          {
            // mu (F - F^-T) + lambda ln(J) F^-T
            const double J     = determinant<dim, double>(F);
            const auto   F_inv = inverse<dim, double>(F);
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                P[i][j] = mu * (F[i][j] - F_inv[j][i]) + lambda * std::log(J) * F_inv[j][i];
            break;
          }
        case MaterialModel::linear:
          {
            double trace = 0;
            for (int i = 0; i < dim; ++i)
              trace += F[i][i] - 1.0;
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                P[i][j] = mu * (F[i][j] + F[j][i] - 2.0 * (i == j)) + (i == j ? lambda * trace : 0.0);
            break;
          }
        case MaterialModel::stvk:
        default:
          {
            // F S with S = 2 mu E + lambda tr(E) I.
            SmallMatrix<dim, double> S{};
            double                   trace = 0;
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                {
                  double c = 0;
                  for (int k = 0; k < dim; ++k)
                    c += F[k][i] * F[k][j];
                  S[i][j] = 0.5 * (c - (i == j ? 1.0 : 0.0));
                }
            for (int i = 0; i < dim; ++i)
              trace += S[i][i];
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j)
                S[i][j] = 2 * mu * S[i][j] + (i == j ? lambda * trace : 0.0);
            P = multiply<dim, double>(F, S);
            break;
          }
      }
    return P;
  }
} // namespace ritr
