#pragma once
// Geometric admissibility of the reference mesh for r-adaptivity (paper 5.3):
//  - boundary maintenance: a boundary node slides in its (approximately) planar facet, or in
//    3D along a (nearly) straight boundary edge; any other boundary node is a corner and is
//    not moved at all. The solver moves each node only within these directions, so the
//    sliding holds exactly instead of through the paper's penalty;
//  - non-inversion: a barrier on each reference element's measure below w_hat (eq. 21), the
//    term terms/measure_barrier_term.h.
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

  // Largest violation |(u_i - u_i^0) . n_i| (facets) or |(u_i - u_i^0) x t_i| (edges).
  template <int dim>
  double sliding_violation(const std::vector<SlidingConstraint<dim>> &c, const Eigen::VectorXd &u);
} // namespace ritr
