#pragma once
// Quadrature rules on the unit simplex, given in barycentric coordinates so that the same
// rule maps onto any cell by X = sum_a lambda_a u_a. Weights sum to the unit simplex's
// measure 1/dim!, so a cell integral is sum_q w_q det J * f(X_q).
//
// The transfer operator takes any such rule (the driver feeds deal.II's Witherden-Vincent
// rules); the simple rules here serve tests and deal.II-free callers.
#include <array>
#include <vector>

namespace ritr
{
  template <int dim>
  struct SimplexQuadrature
  {
    std::vector<std::array<double, dim + 1>> points; // barycentric coordinates
    std::vector<double>                      weights; // sum to 1/dim!

    unsigned int size() const { return weights.size(); }
  };

  // Exact for polynomials of degree 2 (1D: the 2-point Gauss rule, exact to degree 3).
  template <int dim>
  SimplexQuadrature<dim> degree_two_rule();

  // `base` applied on each of the subdivisions^dim congruent sub-simplices of a regular
  // (Freudenthal) subdivision of the unit simplex: as exact as `base` for polynomials, and
  // much better at sampling integrands that are only piecewise smooth inside a cell.
  template <int dim>
  SimplexQuadrature<dim> composite_rule(const SimplexQuadrature<dim> &base,
                                        unsigned int                  subdivisions);

  // Throws std::invalid_argument unless there are as many weights as points, the weights
  // sum to 1/dim! and every point's coordinates sum to one.
  template <int dim>
  void check_rule(const SimplexQuadrature<dim> &rule);
} // namespace ritr
