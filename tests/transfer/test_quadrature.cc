// Simplex quadrature rules: exactness on monomials in barycentric coordinates.
#include <ritr/common/small_matrix.h>
#include <ritr/common/simplex_quadrature.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace ritr;

namespace
{
  // int over the unit simplex of prod_i lambda_i^alpha_i = prod alpha_i! / (dim + |alpha|)!.
  template <int dim>
  double exact_moment(const std::array<int, dim + 1> &alpha)
  {
    double num = 1;
    int    sum = 0;
    for (const int a : alpha)
      {
        num *= factorial(a);
        sum += a;
      }
    return num / factorial(dim + sum);
  }

  // Calls f on every multi-index alpha (dim + 1 entries) with |alpha| <= degree.
  template <int dim>
  void for_each_exponent(const int degree, const std::function<void(const std::array<int, dim + 1> &)> &f)
  {
    std::array<int, dim + 1> alpha{};
    std::function<void(int, int)> rec = [&](const int i, const int left) {
      if (i == dim + 1)
        return f(alpha);
      for (int e = 0; e <= left; ++e)
        {
          alpha[i] = e;
          rec(i + 1, left - e);
        }
      alpha[i] = 0;
    };
    rec(0, degree);
  }

  template <int dim>
  double max_moment_error(const SimplexQuadrature<dim> &rule, const int degree)
  {
    double worst = 0;
    for_each_exponent<dim>(degree, [&](const std::array<int, dim + 1> &alpha) {
      double q = 0;
      for (unsigned int i = 0; i < rule.size(); ++i)
        {
          double v = rule.weights[i];
          for (int b = 0; b <= dim; ++b)
            v *= std::pow(rule.points[i][b], alpha[b]);
          q += v;
        }
      worst = std::max(worst, std::abs(q - exact_moment<dim>(alpha)) / exact_moment<dim>(alpha));
    });
    return worst;
  }

  template <int dim>
  void check_rules()
  {
    const auto base = degree_two_rule<dim>();
    EXPECT_NO_THROW(check_rule(base));
    EXPECT_EQ(base.size(), dim == 1 ? 2u : unsigned(dim + 1));
    EXPECT_LT(max_moment_error(base, dim == 1 ? 3 : 2), 1e-14);
    // Degree 3 is not integrated exactly (so the rule is really of degree 2).
    if (dim > 1)
      EXPECT_GT(max_moment_error(base, 3), 1e-6);

    for (const unsigned int n : {1u, 2u, 3u, 5u})
      {
        const auto composite = composite_rule(base, n);
        EXPECT_NO_THROW(check_rule(composite));
        EXPECT_EQ(composite.size(), base.size() * static_cast<unsigned int>(std::pow(n, dim)));
        EXPECT_LT(max_moment_error(composite, dim == 1 ? 3 : 2), 1e-13) << "n = " << n;
        for (const auto &p : composite.points)
          for (const double l : p)
            EXPECT_GT(l, 0.0);
      }
    // A composite rule converges on smooth integrands it does not integrate exactly.
    const double e1 = max_moment_error(composite_rule(base, 1), 4);
    const double e4 = max_moment_error(composite_rule(base, 4), 4);
    EXPECT_LT(e4, e1 / 10);
  }
} // namespace

TEST(SimplexQuadrature, Rules1D) { check_rules<1>(); }
TEST(SimplexQuadrature, Rules2D) { check_rules<2>(); }
TEST(SimplexQuadrature, Rules3D) { check_rules<3>(); }

TEST(SimplexQuadrature, RejectsMalformedRules)
{
  SimplexQuadrature<2> rule = degree_two_rule<2>();
  rule.weights[0] *= 2;
  EXPECT_THROW(check_rule(rule), std::invalid_argument);
  rule = degree_two_rule<2>();
  rule.points[1][0] += 0.1;
  EXPECT_THROW(check_rule(rule), std::invalid_argument);
  rule = degree_two_rule<2>();
  rule.weights.pop_back();
  EXPECT_THROW(check_rule(rule), std::invalid_argument);
}
