#pragma once
// Measures of simplices as functions of their node coordinates, with first and second
// derivatives (variables: node a, component k at a * dim + k): a cell's signed length, area
// or volume -- the weight of every cell term and the argument of the reference measure
// barrier -- and the unsigned measure of a boundary facet, which weighs the contact terms.
#include <ritr/common/first_order_dual.h>
#include <ritr/common/second_order_dual.h>
#include <ritr/common/small_matrix.h>

#include <Eigen/Core>

#include <array>

namespace ritr
{
  // The signed measure of the cell with nodes `cell` at positions u (flat, node-major), in the
  // dual numbers `Dual` (variables: node a, component k at a * dim + k).
  template <int dim, typename Dual>
  Dual cell_measure_in(const Eigen::VectorXd &u, const std::array<unsigned int, dim + 1> &cell)
  {
    std::array<std::array<Dual, dim>, dim + 1> nodes;
    for (int a = 0; a <= dim; ++a)
      for (int k = 0; k < dim; ++k)
        nodes[a][k] = Dual::variable(a * dim + k, u[cell[a] * dim + k]);
    return simplex_measure<dim, Dual>(nodes);
  }

  // With its gradient and Hessian.
  template <int dim>
  SecondOrderDual<dim *(dim + 1)> cell_measure_derivatives(const Eigen::VectorXd                   &u,
                                                           const std::array<unsigned int, dim + 1> &cell)
  {
    return cell_measure_in<dim, SecondOrderDual<dim *(dim + 1)>>(u, cell);
  }

  // With its gradient alone (first-order outer solves).
  template <int dim>
  FirstOrderDual<dim *(dim + 1)> cell_measure_gradient(const Eigen::VectorXd                   &u,
                                                       const std::array<unsigned int, dim + 1> &cell)
  {
    return cell_measure_in<dim, FirstOrderDual<dim *(dim + 1)>>(u, cell);
  }

  // The measure of the boundary facet with nodes `facet` at positions u: a segment's length in
  // 2D, a triangle's area in 3D, 1 for a rod's end point.
  template <int dim>
  SecondOrderDual<dim * dim> facet_measure_derivatives(const Eigen::VectorXd &u, const std::array<unsigned int, dim> &facet)
  {
    using Dual = SecondOrderDual<dim * dim>;
    std::array<std::array<Dual, dim>, dim> p;
    for (int a = 0; a < dim; ++a)
      for (int k = 0; k < dim; ++k)
        p[a][k] = Dual::variable(a * dim + k, u[facet[a] * dim + k]);
    if constexpr (dim == 1)
      return Dual(1.0);
    else if constexpr (dim == 2)
      return sqrt(square(p[1][0] - p[0][0]) + square(p[1][1] - p[0][1]));
    else
      {
        std::array<Dual, 3> e1, e2;
        for (int k = 0; k < 3; ++k)
          {
            e1[k] = p[1][k] - p[0][k];
            e2[k] = p[2][k] - p[0][k];
          }
        const Dual n0 = e1[1] * e2[2] - e1[2] * e2[1], n1 = e1[2] * e2[0] - e1[0] * e2[2],
                   n2 = e1[0] * e2[1] - e1[1] * e2[0];
        return 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
      }
  }
} // namespace ritr
