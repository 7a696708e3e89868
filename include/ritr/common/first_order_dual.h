#pragma once
// Forward-mode first-order automatic differentiation for small local stencils: a value and
// its gradient with respect to N independent variables. The same kernels that give exact
// Hessians with SecondOrderDual (second_order_dual.h) give gradients alone with this type, at
// O(N) instead of O(N^2) per operation: first-order outer solves need no Hessian.
#include <ritr/common/second_order_dual.h>

#include <Eigen/Core>
#include <cmath>

namespace ritr
{
  template <int N>
  struct FirstOrderDual
  {
    using Gradient = Eigen::Matrix<double, N, 1>;

    double   value = 0.0;
    Gradient grad  = Gradient::Zero();

    FirstOrderDual() = default;
    FirstOrderDual(const double v) : value(v) {}
    // Leaves the gradient unset, for results about to be assigned in full.
    struct Unset
    {};
    explicit FirstOrderDual(Unset) : grad() {}

    // The i-th independent variable with value v.
    static FirstOrderDual variable(const int i, const double v)
    {
      FirstOrderDual d(v);
      d.grad[i] = 1.0;
      return d;
    }

    FirstOrderDual &operator+=(const FirstOrderDual &b)
    {
      value += b.value;
      grad += b.grad;
      return *this;
    }
    FirstOrderDual &operator-=(const FirstOrderDual &b)
    {
      value -= b.value;
      grad -= b.grad;
      return *this;
    }
    FirstOrderDual &operator+=(const double b)
    {
      value += b;
      return *this;
    }
    FirstOrderDual &operator-=(const double b)
    {
      value -= b;
      return *this;
    }
    FirstOrderDual &operator*=(const FirstOrderDual &b) { return *this = *this * b; }
    FirstOrderDual &operator/=(const FirstOrderDual &b) { return *this = *this / b; }
  };

  // Composition with a scalar function f: value f(a), chain rule with f'(a).
  template <int N>
  FirstOrderDual<N> chain(const FirstOrderDual<N> &a, const double f, const double df)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = f;
    r.grad  = df * a.grad;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator+(const FirstOrderDual<N> &a, const FirstOrderDual<N> &b)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = a.value + b.value;
    r.grad  = a.grad + b.grad;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator-(const FirstOrderDual<N> &a, const FirstOrderDual<N> &b)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = a.value - b.value;
    r.grad  = a.grad - b.grad;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator-(const FirstOrderDual<N> &a)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = -a.value;
    r.grad  = -a.grad;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator*(const FirstOrderDual<N> &a, const FirstOrderDual<N> &b)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = a.value * b.value;
    r.grad  = a.value * b.grad + b.value * a.grad;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator/(const FirstOrderDual<N> &a, const FirstOrderDual<N> &b)
  {
    const double      inv = 1.0 / b.value;
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = a.value * inv;
    r.grad  = (a.grad - r.value * b.grad) * inv;
    return r;
  }

  template <int N>
  FirstOrderDual<N> operator+(const FirstOrderDual<N> &a, const double b)
  {
    FirstOrderDual<N> r = a;
    r.value += b;
    return r;
  }
  template <int N>
  FirstOrderDual<N> operator+(const double a, const FirstOrderDual<N> &b)
  {
    return b + a;
  }
  template <int N>
  FirstOrderDual<N> operator-(const FirstOrderDual<N> &a, const double b)
  {
    return a + (-b);
  }
  template <int N>
  FirstOrderDual<N> operator-(const double a, const FirstOrderDual<N> &b)
  {
    return (-b) + a;
  }
  template <int N>
  FirstOrderDual<N> operator*(const FirstOrderDual<N> &a, const double b)
  {
    FirstOrderDual<N> r{typename FirstOrderDual<N>::Unset{}};
    r.value = a.value * b;
    r.grad  = a.grad * b;
    return r;
  }
  template <int N>
  FirstOrderDual<N> operator*(const double a, const FirstOrderDual<N> &b)
  {
    return b * a;
  }
  template <int N>
  FirstOrderDual<N> operator/(const FirstOrderDual<N> &a, const double b)
  {
    return a * (1.0 / b);
  }
  template <int N>
  FirstOrderDual<N> operator/(const double a, const FirstOrderDual<N> &b)
  {
    const double inv = 1.0 / b.value;
    return chain(b, a * inv, -a * inv * inv);
  }

  template <int N>
  bool operator<(const FirstOrderDual<N> &a, const FirstOrderDual<N> &b) { return a.value < b.value; }
  template <int N>
  bool operator<(const FirstOrderDual<N> &a, const double b) { return a.value < b; }
  template <int N>
  bool operator>(const FirstOrderDual<N> &a, const double b) { return a.value > b; }

  template <int N>
  FirstOrderDual<N> sqrt(const FirstOrderDual<N> &a)
  {
    const double s = std::sqrt(a.value);
    return chain(a, s, 0.5 / s);
  }

  template <int N>
  FirstOrderDual<N> log(const FirstOrderDual<N> &a)
  {
    return chain(a, std::log(a.value), 1.0 / a.value);
  }

  template <int N>
  FirstOrderDual<N> square(const FirstOrderDual<N> &a)
  {
    return chain(a, a.value * a.value, 2.0 * a.value);
  }

  template <int N>
  double value_of(const FirstOrderDual<N> &a)
  {
    return a.value;
  }
} // namespace ritr
