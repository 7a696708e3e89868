#pragma once
// Active contact constraints and the weighted IPC barrier potential
//
//   B(V) = sum_k w_k m_k(V) b(d_k(V), dhat^2)
//
// with d_k the squared distance of primitive pair k (classified as in distance.h), b the
// IPC barrier, m_k the edge-edge mollifier (1 for other kinds) and w_k a weight supplied by
// the caller (reference boundary measure). B is not multiplied by the stiffness kappa.
//
// Numbering: V is n x dim, gradients have n*dim entries (entry v*dim + k) and Hessians
// are triplets in the same numbering.
#include <ritr/common/triplets.h>
#include <ritr/contact/broad_phase.h>
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/distance.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <utility>
#include <vector>

namespace ritr::contact
{
  enum class WeightOwner
  {
    vertex, // ConstraintWeights::vertex_weights[weight_index]
    edge    // ConstraintWeights::edge_weights[weight_index]
  };

  struct Constraint
  {
    ContactKind        kind       = ContactKind::vertex_vertex;
    std::array<int, 4> vertices   = {{-1, -1, -1, -1}}; // stencil, ordering as in distance.h
    int                n_vertices = 0;
    int                first      = -1; // primitive ids, see Candidate
    int                second     = -1;

    // Point kinds: the point vertex (vertex_vertex: `first`); edge_edge: the first edge.
    WeightOwner weight_owner = WeightOwner::vertex;
    int         weight_index = -1;

    // edge_edge only: mollifier threshold eps_x from rest positions (0 otherwise).
    double mollifier_threshold = 0.0;

    // At the positions the constraint was built with (informational: evaluation always
    // reclassifies).
    DistanceType distance_type = DistanceType::point_point;
    double       distance_sqr  = 0.0;
  };

  // Per-constraint weights. An empty vector means all weights of that kind are 1.
  struct ConstraintWeights
  {
    std::vector<double> vertex_weights; // per collision vertex
    std::vector<double> edge_weights;   // per surface edge (3D edge-edge)

    double weight(const Constraint &c) const
    {
      const auto &w = c.weight_owner == WeightOwner::vertex ? vertex_weights : edge_weights;
      return w.empty() ? 1.0 : w[c.weight_index];
    }
  };

  // Active set at positions V: all candidate pairs with squared distance < dhat^2.
  // rest_V (reference positions) is used for the edge-edge mollifier threshold. Ordered
  // deterministically (by kind, first, second).
  template <int dim>
  std::vector<Constraint> build_constraints(const CollisionSurface<dim> &surface,
                                            const Eigen::MatrixXd &V,
                                            const Eigen::MatrixXd &rest_V, double dhat);

  // Same, from a given candidate list (e.g. reused from a wider broad phase).
  template <int dim>
  std::vector<Constraint> build_constraints(const CollisionSurface<dim> &surface,
                                            const std::vector<Candidate> &candidates,
                                            const Eigen::MatrixXd &V,
                                            const Eigen::MatrixXd &rest_V, double dhat);

  // Stencil positions of a constraint.
  template <int dim>
  StencilVector<dim> gather_stencil(const Constraint &c, const Eigen::MatrixXd &V);

  // Squared distance of one constraint at V.
  template <int dim>
  double constraint_distance_sqr(const Constraint &c, const Eigen::MatrixXd &V);

  // Unscaled weighted barrier B(V); +inf if some constraint has d <= 0.
  template <int dim>
  double barrier_energy(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                        double dhat, const ConstraintWeights &weights);

  // dB/dV (size n*dim). Requires d > 0 for every constraint.
  template <int dim>
  Eigen::VectorXd barrier_gradient(const std::vector<Constraint> &constraints,
                                   const Eigen::MatrixXd &V, double dhat,
                                   const ConstraintWeights &weights);

  // d2B/dV2 as triplets (duplicates to be summed). With project_psd each constraint's local
  // Hessian is projected to the PSD cone before assembly.
  template <int dim>
  Triplets
  barrier_hessian(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                  double dhat, const ConstraintWeights &weights, bool project_psd = true);
  // Both at once from one evaluation of each local Hessian: the exact one and the projected
  // one, entry for entry in the same order.
  template <int dim>
  std::pair<Triplets, Triplets>
  barrier_hessian_and_projection(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                                 double dhat, const ConstraintWeights &weights);

  // Unweighted barrier of one constraint (m b, including the mollifier) and its gradient
  // w.r.t. the constraint's stencil positions (constraint.vertices order, n_vertices*dim
  // entries). With these, B = sum_k w_k value_k and a caller whose weights depend on the
  // reference configuration X can form dB/dX|_weights = sum_k value_k dw_k/dX.
  struct BarrierTerm
  {
    double                                                    value = 0.0;
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 12, 1> gradient;
  };
  template <int dim>
  std::vector<BarrierTerm> unweighted_barrier_terms(const std::vector<Constraint> &constraints,
                                                    const Eigen::MatrixXd &V, double dhat);

  // Smallest UNSQUARED distance between any two candidate primitives (non-adjacent, not
  // obstacle-obstacle) at V; +inf if there are no such pairs. Exact: uses the broad phase
  // with a growing inflation until the closest pair is certainly found.
  template <int dim>
  double minimum_distance(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V);

  // Smallest unsquared distance over a constraint set at V (+inf if empty). Cheap; enough
  // for update_barrier_stiffness, which only cares about distances below dhat.
  template <int dim>
  double minimum_distance(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V);
} // namespace ritr::contact
