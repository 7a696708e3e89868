#include <ritr/elasticity/cell_energy.h>
#include <ritr/mesh/simplex_rules.h>

namespace ritr
{
  template <int dim>
  const std::array<std::array<double, dim + 1>, dim + 1> &unit_mass_coefficients()
  {
    static const auto coefficients = [] {
      // Degree-2 rule: exact for products of two linear shape functions.
      const auto rule = gauss_simplex_rule<dim>(2);
      std::array<std::array<double, dim + 1>, dim + 1> m{};
      double total = 0;
      for (unsigned int p = 0; p < rule.size(); ++p)
        {
          total += rule.weights[p];
          for (int a = 0; a <= dim; ++a)
            for (int b = 0; b <= dim; ++b)
              m[a][b] += rule.weights[p] * rule.points[p][a] * rule.points[p][b];
        }
      for (auto &row : m)
        for (auto &v : row)
          v /= total;
      return m;
    }();
    return coefficients;
  }

  template const std::array<std::array<double, 2>, 2> &unit_mass_coefficients<1>();
  template const std::array<std::array<double, 3>, 3> &unit_mass_coefficients<2>();
  template const std::array<std::array<double, 4>, 4> &unit_mass_coefficients<3>();
} // namespace ritr
