#pragma once
// Tiny dense matrices (dim x dim, dim <= 3) templated on the scalar type, so that the same
// element kernels run on doubles and on SecondOrderDual numbers.
#include <array>

namespace ritr
{
  template <int dim, typename Scalar>
  using SmallMatrix = std::array<std::array<Scalar, dim>, dim>;

  template <int dim, typename Scalar>
  Scalar determinant(const SmallMatrix<dim, Scalar> &a)
  {
    if constexpr (dim == 1)
      return a[0][0];
    else if constexpr (dim == 2)
      return a[0][0] * a[1][1] - a[0][1] * a[1][0];
    else
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  }

  // Inverse via the adjugate; the caller guarantees a non-zero determinant.
  template <int dim, typename Scalar>
  SmallMatrix<dim, Scalar> inverse(const SmallMatrix<dim, Scalar> &a)
  {
    SmallMatrix<dim, Scalar> r;
    const Scalar det = determinant<dim, Scalar>(a);
    if constexpr (dim == 1)
      r[0][0] = 1.0 / det;
    else if constexpr (dim == 2)
      {
        r[0][0] = a[1][1] / det;
        r[0][1] = -a[0][1] / det;
        r[1][0] = -a[1][0] / det;
        r[1][1] = a[0][0] / det;
      }
    else
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          {
            // Cofactor of a[j][i] (transposed) divided by the determinant.
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            r[i][j] = (a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / det;
          }
    return r;
  }

  template <int dim, typename Scalar>
  SmallMatrix<dim, Scalar> multiply(const SmallMatrix<dim, Scalar> &a,
                                    const SmallMatrix<dim, Scalar> &b)
  {
    SmallMatrix<dim, Scalar> r;
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        {
          Scalar s = a[i][0] * b[0][j];
          for (int k = 1; k < dim; ++k)
            s = s + a[i][k] * b[k][j];
          r[i][j] = s;
        }
    return r;
  }

  // Edge matrix [p1 - p0, ..., pd - p0] of a simplex whose node coordinates are
  // nodes[a][k] (node a, component k).
  template <int dim, typename Scalar>
  SmallMatrix<dim, Scalar> edge_matrix(const std::array<std::array<Scalar, dim>, dim + 1> &nodes)
  {
    SmallMatrix<dim, Scalar> d;
    for (int k = 0; k < dim; ++k)
      for (int a = 0; a < dim; ++a)
        d[k][a] = nodes[a + 1][k] - nodes[0][k];
    return d;
  }

  constexpr double factorial(const int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

  // Signed length / area / volume of a simplex.
  template <int dim, typename Scalar>
  Scalar simplex_measure(const std::array<std::array<Scalar, dim>, dim + 1> &nodes)
  {
    return determinant<dim, Scalar>(edge_matrix<dim, Scalar>(nodes)) / factorial(dim);
  }
} // namespace ritr
