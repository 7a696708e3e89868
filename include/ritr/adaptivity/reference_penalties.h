#pragma once
// Geometric admissibility of the reference mesh for r-adaptivity (paper 5.3):
//  - boundary maintenance: a boundary node slides in its (approximately) planar facet, or in
//    3D along a (nearly) straight boundary edge; any other boundary node is a corner and is
//    not moved at all. The solver moves each node only within these directions, so the
//    sliding holds exactly instead of through the paper's penalty;
//  - non-inversion: a barrier on each reference element's measure below w_hat (eq. 21),
//    with gradient and per-cell PSD-projected Hessian in u.
#include <ritr/common/second_order_dual.h>
#include <ritr/mesh/simplex_mesh.h>

#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  enum class SlidingKind
  {
    interior,  // free
    facet,     // slides in the plane with normal `direction`
    edge,      // (3D) slides along the line with tangent `direction`
    corner     // fixed
  };

  template <int dim>
  struct SlidingConstraint
  {
    SlidingKind kind = SlidingKind::interior;
    Vec<dim>    direction = Vec<dim>::Zero();  // facet normal or edge tangent (unit)
    Vec<dim>    anchor    = Vec<dim>::Zero();  // initial reference position u_i^0
  };

  // Classifies every node at the initial reference positions with tolerance eps_b on
  // 1 - n_i . n_t (facets) and on c_jk = t_j . t_k + 1 (straight edges, 3D).
  template <int dim>
  std::vector<SlidingConstraint<dim>> classify_sliding(const SimplexMesh<dim> &mesh, double eps_b);

  using Triplets = std::vector<Eigen::Triplet<double>>;

  // Largest violation |(u_i - u_i^0) . n_i| (facets) or |(u_i - u_i^0) x t_i| (edges).
  template <int dim>
  double sliding_violation(const std::vector<SlidingConstraint<dim>> &c, const Eigen::VectorXd &u);

  // The measure of `cell` at reference positions u with its gradient and Hessian in the
  // cell's dim (dim + 1) node coordinates (node a, component k at a * dim + k).
  template <int dim>
  SecondOrderDual<dim *(dim + 1)> cell_measure_derivatives(const Eigen::VectorXd &u,
                                                           const typename SimplexMesh<dim>::Cell &cell);

  // sum_t kappa b(w_t(u)) with b(w) = -(w - w_hat)^2 ln(w / w_hat) for 0 < w < w_hat
  // (+infinity for w <= 0). With `project_psd` each element's Hessian block is projected to
  // be positive semi-definite (the truncated Hessian of the outer solve).
  template <int dim>
  double reference_measure_barrier(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &u, double w_hat,
                                   double kappa, Eigen::VectorXd *gradient = nullptr,
                                   Triplets *hessian = nullptr, bool project_psd = true);
} // namespace ritr
