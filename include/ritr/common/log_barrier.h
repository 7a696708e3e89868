#pragma once
// The IPC log barrier b(s) = -(s - s_hat)^2 ln(s / s_hat) on (0, s_hat), 0 beyond and +inf at
// s <= 0, with its first two derivatives. Contact applies it to squared distances (s_hat =
// dhat^2, no square roots in the kernels); r-adaptivity to reference cell measures (s_hat =
// w_hat, paper eq. 21).
#include <cmath>
#include <limits>

namespace ritr
{
  inline double log_barrier(const double s, const double s_hat)
  {
    if (s <= 0.0)
      return std::numeric_limits<double>::infinity();
    if (s >= s_hat)
      return 0.0;
    const double r = s - s_hat;
    return -r * r * std::log(s / s_hat);
  }

  // db/ds.
  inline double log_barrier_derivative(const double s, const double s_hat)
  {
    if (s >= s_hat)
      return 0.0;
    const double r = s - s_hat;
    return -2.0 * r * std::log(s / s_hat) - r * r / s;
  }

  // d2b/ds2.
  inline double log_barrier_second_derivative(const double s, const double s_hat)
  {
    if (s >= s_hat)
      return 0.0;
    const double r = s - s_hat;
    return -2.0 * std::log(s / s_hat) - 4.0 * r / s + r * r / (s * s);
  }
} // namespace ritr
