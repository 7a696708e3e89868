#pragma once
// Small helpers the two Newton iterations (newton.cc, newton_trust_region.cc) share: the free
// entries of a state vector (free_index[i] >= 0: its row in the reduced system) and the
// energy's round-off.
#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <vector>

namespace ritr::newton_detail
{
  // Round-off of an energy value: it is a sum of many terms of about its own size, each
  // rounded to machine precision, so differences below ~1000 ulps carry no information.
  inline double energy_round_off(const double energy)
  {
    return 1e3 * std::numeric_limits<double>::epsilon() * std::abs(energy);
  }

  // |v| over the free entries.
  inline double free_norm(const Eigen::VectorXd &v, const std::vector<int> &free_index)
  {
    double sum = 0;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (free_index[i] >= 0)
        sum += v[i] * v[i];
    return std::sqrt(sum);
  }

  // The reduced vector of v's free entries.
  inline Eigen::VectorXd gather_free(const Eigen::VectorXd &v, const std::vector<int> &free_index, const Eigen::Index n_free)
  {
    Eigen::VectorXd v_free(n_free);
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (free_index[i] >= 0)
        v_free[free_index[i]] = v[i];
    return v_free;
  }

  // The free entries of `out` from the reduced vector `v_free`; the others are left as they are.
  inline void scatter_free(const Eigen::VectorXd &v_free, const std::vector<int> &free_index, Eigen::VectorXd &out)
  {
    for (Eigen::Index i = 0; i < out.size(); ++i)
      if (free_index[i] >= 0)
        out[i] = v_free[free_index[i]];
  }
} // namespace ritr::newton_detail
