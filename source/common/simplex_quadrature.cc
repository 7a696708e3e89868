#include <ritr/common/small_matrix.h>
#include <ritr/common/simplex_quadrature.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace ritr
{
  template <int dim>
  SimplexQuadrature<dim> degree_two_rule()
  {
    SimplexQuadrature<dim> rule;
    if constexpr (dim == 1)
      {
        const double a = 0.5 - 0.5 / std::sqrt(3.0);
        rule.points    = {{{1 - a, a}}, {{a, 1 - a}}};
        rule.weights   = {0.5, 0.5};
      }
    else
      {
        // dim + 1 points symmetric about the centroid; the offset makes the second moments
        // exact (2D: 1/6, 3D: (5 - sqrt 5)/20).
        const double b = dim == 2 ? 1.0 / 6.0 : (5.0 - std::sqrt(5.0)) / 20.0;
        const double a = 1.0 - dim * b;
        for (int i = 0; i <= dim; ++i)
          {
            std::array<double, dim + 1> p;
            p.fill(b);
            p[i] = a;
            rule.points.push_back(p);
            rule.weights.push_back(1.0 / factorial(dim + 1));
          }
      }
    return rule;
  }

  template <int dim>
  SimplexQuadrature<dim> composite_rule(const SimplexQuadrature<dim> &base,
                                        const unsigned int            subdivisions)
  {
    if (subdivisions == 0)
      throw std::invalid_argument("composite_rule: subdivisions must be positive");
    // Work in the simplex T = {1 >= y_1 >= ... >= y_dim >= 0}, which the Freudenthal
    // (Kuhn) triangulation of the grid with spacing 1/n subdivides exactly, then map to
    // barycentric coordinates lambda = (1 - y_1, y_1 - y_2, ..., y_dim). The map is
    // unimodular, so each sub-simplex carries the fraction 1/n^dim of the weight.
    const int    n     = static_cast<int>(subdivisions);
    const double scale = std::pow(double(n), -dim);

    std::array<int, dim> perm;
    std::iota(perm.begin(), perm.end(), 0);
    std::vector<std::array<int, dim>> permutations;
    do
      permutations.push_back(perm);
    while (std::next_permutation(perm.begin(), perm.end()));

    SimplexQuadrature<dim> rule;
    std::array<int, dim>   corner{};
    int                    n_cubes = 1;
    for (int k = 0; k < dim; ++k)
      n_cubes *= n;
    for (int cube = 0; cube < n_cubes; ++cube)
      {
        for (int k = 0, c = cube; k < dim; ++k, c /= n)
          corner[k] = c % n;
        for (const auto &p : permutations)
          {
            // Vertices of the Kuhn simplex: corner, then add unit steps in the order p.
            std::array<std::array<double, dim>, dim + 1> v;
            for (int k = 0; k < dim; ++k)
              v[0][k] = corner[k];
            for (int j = 0; j < dim; ++j)
              {
                v[j + 1] = v[j];
                v[j + 1][p[j]] += 1.0;
              }
            // Inside T iff its centroid is (the triangulation respects T's facets).
            std::array<double, dim> centroid{};
            for (int j = 0; j <= dim; ++j)
              for (int k = 0; k < dim; ++k)
                centroid[k] += v[j][k] / (dim + 1);
            bool inside = centroid[0] < n && centroid[dim - 1] > 0;
            for (int k = 0; k + 1 < dim; ++k)
              inside = inside && centroid[k] > centroid[k + 1];
            if (!inside)
              continue;
            for (unsigned int q = 0; q < base.size(); ++q)
              {
                std::array<double, dim> y{};
                for (int j = 0; j <= dim; ++j)
                  for (int k = 0; k < dim; ++k)
                    y[k] += base.points[q][j] * v[j][k] / n;
                std::array<double, dim + 1> lambda;
                lambda[0] = 1.0 - y[0];
                for (int k = 1; k < dim; ++k)
                  lambda[k] = y[k - 1] - y[k];
                lambda[dim] = y[dim - 1];
                rule.points.push_back(lambda);
                rule.weights.push_back(base.weights[q] * scale);
              }
          }
      }
    return rule;
  }

  template <int dim>
  void check_rule(const SimplexQuadrature<dim> &rule)
  {
    if (rule.points.size() != rule.weights.size() || rule.weights.empty())
      throw std::invalid_argument("simplex quadrature: need as many points as weights (> 0)");
    const double sum = std::accumulate(rule.weights.begin(), rule.weights.end(), 0.0);
    if (std::abs(sum * factorial(dim) - 1.0) > 1e-10)
      throw std::invalid_argument("simplex quadrature: weights sum to " + std::to_string(sum) +
                                  ", expected 1/dim!");
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        const double s = std::accumulate(rule.points[q].begin(), rule.points[q].end(), 0.0);
        if (std::abs(s - 1.0) > 1e-10)
          throw std::invalid_argument("simplex quadrature: point " + std::to_string(q) +
                                      " is not in barycentric coordinates");
      }
  }

#define RITR_INSTANTIATE(dim)                                                                  \
  template SimplexQuadrature<dim> degree_two_rule<dim>();                                      \
  template SimplexQuadrature<dim> composite_rule<dim>(const SimplexQuadrature<dim> &,          \
                                                      unsigned int);                           \
  template void                   check_rule<dim>(const SimplexQuadrature<dim> &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
