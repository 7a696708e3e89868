#pragma once
// A term sum as the derivative tests look at it: every quantity at a state z and a reference
// mesh u, with the collision candidates built at z, so that finite differences in either can
// be taken by calling the same function at nearby points.
#include <ritr/terms/term_sum.h>

#include "finite_difference.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

namespace ritr::test_support
{
  // The list with the changes applied (the projected Hessian from the exact one's list).
  inline Triplets with_changes(Triplets t, const TripletChanges &changes)
  {
    for (const auto &[position, value] : changes)
      t[position] = Eigen::Triplet<double>(t[position].row(), t[position].col(), t[position].value() + value);
    return t;
  }

  template <int dim>
  struct TermProbe
  {
    TermSum<dim> &terms;

    // R(z, u) (every term) and E(z; u) (the terms of the state).
    double objective(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
    {
      terms.set_reference(u);
      return terms.objective(z, terms.candidates_at(z));
    }
    double energy(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
    {
      terms.set_reference(u);
      return terms.energy(z, terms.candidates_at(z));
    }
    // dE/dz and d2E/dz2 (dense).
    Eigen::VectorXd gradient(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
    {
      terms.set_reference(u);
      Eigen::VectorXd g = Eigen::VectorXd::Zero(z.size());
      terms.add_energy_gradient(z, terms.candidates_at(z), g);
      return g;
    }
    Eigen::MatrixXd hessian(const Eigen::VectorXd &z, const Eigen::VectorXd &u, const bool project) const
    {
      terms.set_reference(u);
      MatrixAssembly<dim> h(terms.mesh().cells);
      terms.add_energy_hessian(z, terms.candidates_at(z), project, h);
      return dense(h.to_triplets(), z.size(), z.size());
    }
    // The trust-region Newton's one-pass Hessians, dense: the exact one and the projected one
    // as exact plus the projection's change.
    std::pair<Eigen::MatrixXd, Eigen::MatrixXd> hessian_and_projected(const Eigen::VectorXd &z,
                                                                      const Eigen::VectorXd &u) const
    {
      terms.set_reference(u);
      MatrixAssembly<dim> assembly(terms.mesh().cells);
      terms.add_energy_hessian_and_projection(z, terms.candidates_at(z), assembly);
      const Triplets exact = assembly.to_triplets();
      TripletChanges changes;
      assembly.append_changes(0, changes);
      return {dense(exact, z.size(), z.size()), dense(with_changes(exact, changes), z.size(), z.size())};
    }
    // They equal the two Hessians assembled apart; returns whether the projection changed
    // anything at (z, u).
    bool expect_one_pass_hessians_match(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
    {
      const auto [exact, projected] = hessian_and_projected(z, u);
      const Eigen::MatrixXd apart   = hessian(z, u, true);
      EXPECT_EQ((exact - hessian(z, u, false)).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_LE((projected - apart).cwiseAbs().maxCoeff(), 1e-12 * exact.cwiseAbs().maxCoeff());
      return (apart - exact).cwiseAbs().maxCoeff() > 1e-8 * exact.cwiseAbs().maxCoeff();
    }
    // R's derivatives in u with the coupling blocks.
    typename TermSum<dim>::ReferenceDerivatives derivatives(const Eigen::VectorXd &z, const Eigen::VectorXd &u,
                                                            const ReferenceBlock block = ReferenceBlock::exact) const
    {
      terms.set_reference(u);
      return terms.reference_derivatives(z, terms.candidates_at(z), block, true);
    }
    // dR/du alone, by the first-order path (what the quasi-Newton outer solve takes).
    Eigen::VectorXd reference_gradient(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
    {
      terms.set_reference(u);
      return terms.reference_gradient(z, terms.candidates_at(z));
    }
  };

  // u with every entry moved by a uniform random amount in [-size, size].
  inline Eigen::VectorXd jitter(const Eigen::VectorXd &u, const double size, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> d(-size, size);
    Eigen::VectorXd                        r = u;
    for (Eigen::Index i = 0; i < r.size(); ++i)
      r[i] += d(rng);
    return r;
  }
} // namespace ritr::test_support
