// The trust-region Newton solve may precondition later iterations with an earlier
// iteration's factor (NewtonSettings::reuse_factorizations_from): its model is still each
// iteration's exact Hessian, so it reaches the same minimiser, with fewer factorizations.
#include <ritr/solver/newton.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace ritr;

namespace
{
  // A convex chain whose curvature changes along the way: sum_i cosh(2 z_i) - c_i z_i plus,
  // between neighbours, d^2 / 2 + d^4 / 4 of their difference d.
  class Chain : public NewtonObjective
  {
  public:
    explicit Chain(const int n) : c_(n)
    {
      for (int i = 0; i < n; ++i)
        c_[i] = 2 + 3 * std::sin(i);
    }

    double value(const Eigen::VectorXd &z) override
    {
      double f = 0;
      for (Eigen::Index i = 0; i < z.size(); ++i)
        f += std::cosh(2 * z[i]) - c_[i] * z[i];
      for (Eigen::Index i = 0; i + 1 < z.size(); ++i)
        {
          const double d = z[i + 1] - z[i];
          f += d * d / 2 + d * d * d * d / 4;
        }
      return f;
    }

    void gradient(const Eigen::VectorXd &z, Eigen::VectorXd &g) override
    {
      for (Eigen::Index i = 0; i < z.size(); ++i)
        g[i] += 2 * std::sinh(2 * z[i]) - c_[i];
      for (Eigen::Index i = 0; i + 1 < z.size(); ++i)
        {
          const double d = z[i + 1] - z[i], s = d + d * d * d;
          g[i + 1] += s;
          g[i] -= s;
        }
    }

    void hessian(const Eigen::VectorXd &z, Triplets &h, bool) override
    {
      for (Eigen::Index i = 0; i < z.size(); ++i)
        h.emplace_back(i, i, 4 * std::cosh(2 * z[i]));
      for (Eigen::Index i = 0; i + 1 < z.size(); ++i)
        {
          const double d = z[i + 1] - z[i], w = 1 + 3 * d * d;
          const int    a = static_cast<int>(i), b = a + 1;
          h.emplace_back(a, a, w);
          h.emplace_back(b, b, w);
          h.emplace_back(a, b, -w);
          h.emplace_back(b, a, -w);
        }
    }

  private:
    Eigen::VectorXd c_;
  };

  struct Solve
  {
    NewtonResult    result;
    Eigen::VectorXd z;
    unsigned int    factorizations = 0;
  };

  Solve solve(const double reuse_from)
  {
    const int        n = 200;
    Chain            chain(n);
    NewtonSolver     newton;
    NewtonSettings   settings;
    settings.tolerance                 = 1e-12;
    settings.max_iterations            = 200;
    settings.projection                = HessianProjection::trust_region;
    settings.reuse_factorizations_from = reuse_from;
    Solve s;
    s.z              = Eigen::VectorXd::Zero(n);
    s.result         = newton.minimize(chain, s.z, std::vector<bool>(n, false), Eigen::VectorXd::Zero(n), settings);
    s.factorizations = newton.n_factorizations();
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    chain.gradient(s.z, g);
    EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-9) << "reuse from " << reuse_from;
    return s;
  }
} // namespace

TEST(NewtonFactorReuse, SameMinimiserWithFewerFactorizations)
{
  const Solve fresh  = solve(std::numeric_limits<double>::infinity());
  const Solve reused = solve(0);
  ASSERT_TRUE(fresh.result.converged()) << fresh.result.failure;
  ASSERT_TRUE(reused.result.converged()) << reused.result.failure;
  EXPECT_LT((fresh.z - reused.z).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_EQ(fresh.factorizations, fresh.result.iterations + 1) << "one factorization per iteration";
  EXPECT_LT(reused.factorizations, fresh.factorizations / 2) << reused.result.iterations << " iterations";
}
