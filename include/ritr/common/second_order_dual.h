#pragma once
// Forward-mode second-order automatic differentiation for small local stencils.
//
// A SecondOrderDual<N> carries a value, its gradient and its Hessian with respect to N
// independent variables. Local energy kernels (a distance function, a strain energy
// density) are written once as templates on the scalar type; instantiating them with
// SecondOrderDual gives exact first and second derivatives, which the tests then check
// against finite differences. Stencils are small (N <= 24), so the O(N^2) cost per
// operation is acceptable outside the innermost hot loops. The Hessians' outer products are
// lazy products, so that each result is one pass over its N^2 entries (a plain product in a
// sum is evaluated into a temporary first).
#include <Eigen/Core>
#include <cmath>
#include <type_traits>

namespace ritr
{
  // Kernels call log/sqrt unqualified so that they work for doubles and dual numbers alike.
  using std::log;
  using std::sqrt;

  template <int N>
  struct SecondOrderDual
  {
    using Gradient = Eigen::Matrix<double, N, 1>;
    using Hessian  = Eigen::Matrix<double, N, N>;

    double   value = 0.0;
    Gradient grad  = Gradient::Zero();
    Hessian  hess  = Hessian::Zero();

    SecondOrderDual() = default;
    SecondOrderDual(const double v) : value(v) {}
    // Leaves the derivatives unset, for results about to be assigned in full: the arithmetic
    // below would otherwise clear N + N^2 numbers it then overwrites. (The member list
    // overrides the Zero() initialisers; Eigen's default constructor leaves values unset.)
    struct Unset
    {};
    explicit SecondOrderDual(Unset) : grad(), hess() {}

    // The i-th independent variable with value v.
    static SecondOrderDual variable(const int i, const double v)
    {
      SecondOrderDual d(v);
      d.grad[i] = 1.0;
      return d;
    }

    SecondOrderDual &operator+=(const SecondOrderDual &b)
    {
      value += b.value;
      grad += b.grad;
      hess += b.hess;
      return *this;
    }
    SecondOrderDual &operator-=(const SecondOrderDual &b)
    {
      value -= b.value;
      grad -= b.grad;
      hess -= b.hess;
      return *this;
    }
    // With a constant only the value changes.
    SecondOrderDual &operator+=(const double b)
    {
      value += b;
      return *this;
    }
    SecondOrderDual &operator-=(const double b)
    {
      value -= b;
      return *this;
    }
    SecondOrderDual &operator*=(const SecondOrderDual &b) { return *this = *this * b; }
    SecondOrderDual &operator/=(const SecondOrderDual &b) { return *this = *this / b; }
  };

  // Composition with a scalar function f: value f(a), chain rule with f'(a) and f''(a).
  template <int N>
  SecondOrderDual<N> chain(const SecondOrderDual<N> &a, const double f, const double df,
                           const double d2f)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = f;
    r.grad  = df * a.grad;
    r.hess  = df * a.hess + (d2f * a.grad).lazyProduct(a.grad.transpose());
    return r;
  }

  template <int N>
  SecondOrderDual<N> operator+(const SecondOrderDual<N> &a, const SecondOrderDual<N> &b)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = a.value + b.value;
    r.grad  = a.grad + b.grad;
    r.hess  = a.hess + b.hess;
    return r;
  }

  template <int N>
  SecondOrderDual<N> operator-(const SecondOrderDual<N> &a, const SecondOrderDual<N> &b)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = a.value - b.value;
    r.grad  = a.grad - b.grad;
    r.hess  = a.hess - b.hess;
    return r;
  }

  template <int N>
  SecondOrderDual<N> operator-(const SecondOrderDual<N> &a)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = -a.value;
    r.grad  = -a.grad;
    r.hess  = -a.hess;
    return r;
  }

  template <int N>
  SecondOrderDual<N> operator*(const SecondOrderDual<N> &a, const SecondOrderDual<N> &b)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = a.value * b.value;
    r.grad  = a.value * b.grad + b.value * a.grad;
    r.hess  = a.value * b.hess + b.value * a.hess + a.grad.lazyProduct(b.grad.transpose()) +
             b.grad.lazyProduct(a.grad.transpose());
    return r;
  }

  template <int N>
  SecondOrderDual<N> operator/(const SecondOrderDual<N> &a, const SecondOrderDual<N> &b)
  {
    // r = a / b from a = r b, differentiated once and twice.
    const double       inv = 1.0 / b.value;
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = a.value * inv;
    r.grad  = (a.grad - r.value * b.grad) * inv;
    r.hess  = (a.hess - r.value * b.hess - r.grad.lazyProduct(b.grad.transpose()) -
              b.grad.lazyProduct(r.grad.transpose())) *
             inv;
    return r;
  }

  // Mixed operations with plain doubles avoid building dual numbers for constants.
  template <int N>
  SecondOrderDual<N> operator+(const SecondOrderDual<N> &a, const double b)
  {
    SecondOrderDual<N> r = a;
    r.value += b;
    return r;
  }
  template <int N>
  SecondOrderDual<N> operator+(const double a, const SecondOrderDual<N> &b)
  {
    return b + a;
  }
  template <int N>
  SecondOrderDual<N> operator-(const SecondOrderDual<N> &a, const double b)
  {
    return a + (-b);
  }
  template <int N>
  SecondOrderDual<N> operator-(const double a, const SecondOrderDual<N> &b)
  {
    return (-b) + a;
  }
  template <int N>
  SecondOrderDual<N> operator*(const SecondOrderDual<N> &a, const double b)
  {
    SecondOrderDual<N> r{typename SecondOrderDual<N>::Unset{}};
    r.value = a.value * b;
    r.grad  = a.grad * b;
    r.hess  = a.hess * b;
    return r;
  }
  template <int N>
  SecondOrderDual<N> operator*(const double a, const SecondOrderDual<N> &b)
  {
    return b * a;
  }
  template <int N>
  SecondOrderDual<N> operator/(const SecondOrderDual<N> &a, const double b)
  {
    return a * (1.0 / b);
  }
  template <int N>
  SecondOrderDual<N> operator/(const double a, const SecondOrderDual<N> &b)
  {
    const double inv = 1.0 / b.value;
    return chain(b, a * inv, -a * inv * inv, 2.0 * a * inv * inv * inv);
  }

  template <int N>
  bool operator<(const SecondOrderDual<N> &a, const SecondOrderDual<N> &b) { return a.value < b.value; }
  template <int N>
  bool operator<(const SecondOrderDual<N> &a, const double b) { return a.value < b; }
  template <int N>
  bool operator>(const SecondOrderDual<N> &a, const double b) { return a.value > b; }

  template <int N>
  SecondOrderDual<N> sqrt(const SecondOrderDual<N> &a)
  {
    const double s = std::sqrt(a.value);
    return chain(a, s, 0.5 / s, -0.25 / (s * a.value));
  }

  template <int N>
  SecondOrderDual<N> log(const SecondOrderDual<N> &a)
  {
    return chain(a, std::log(a.value), 1.0 / a.value, -1.0 / (a.value * a.value));
  }

  template <int N>
  SecondOrderDual<N> square(const SecondOrderDual<N> &a)
  {
    return chain(a, a.value * a.value, 2.0 * a.value, 2.0);
  }

  inline double square(const double a) { return a * a; }

  // A scalar about to be assigned: 0 for a double, a dual number with its derivatives unset.
  template <typename S>
  S unset()
  {
    if constexpr (std::is_same_v<S, double>)
      return 0.0;
    else
      return S(typename S::Unset{});
  }

  // Value of a plain double or of a dual number, for code templated on the scalar type.
  inline double value_of(const double a) { return a; }
  template <int N>
  double value_of(const SecondOrderDual<N> &a)
  {
    return a.value;
  }
} // namespace ritr
