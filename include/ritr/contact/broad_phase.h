#pragma once
// Broad phase: candidate primitive pairs whose (inflated) axis-aligned bounding boxes
// overlap, found with the shared AABB tree (common/aabb_tree.h) and TBB-parallel queries.
#include <ritr/common/aabb_tree.h>
#include <ritr/contact/collision_surface.h>

#include <Eigen/Core>

#include <array>
#include <limits>
#include <tuple>
#include <vector>

namespace ritr::contact
{
  // A candidate primitive pair.
  //  vertex_vertex:  first, second = vertices
  //  point_edge:     first = vertex, second = edge
  //  point_triangle: first = vertex, second = face
  //  edge_edge:      first, second = edges
  // For the symmetric kinds (vertex_vertex, edge_edge) `first` is a body primitive when
  // exactly one of the two is an obstacle, otherwise the smaller index; the constraint
  // weight is that of `first`.
  struct Candidate
  {
    ContactKind kind   = ContactKind::vertex_vertex;
    int         first  = -1;
    int         second = -1;

    bool operator<(const Candidate &o) const
    {
      return std::tie(kind, first, second) < std::tie(o.kind, o.first, o.second);
    }
    bool operator==(const Candidate &o) const
    {
      return kind == o.kind && first == o.first && second == o.second;
    }
  };

  // The stencil vertices of a candidate (ordering as in distance.h) and their count.
  template <int dim>
  int stencil_vertices(const CollisionSurface<dim> &surface, const Candidate &c,
                       std::array<int, 4> &vertices);

  // All candidate pairs (not sharing a vertex, not obstacle-obstacle) that may be closer
  // than `inflation` at positions V: every pair at distance < inflation is returned.
  // Sorted, without duplicates.
  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V, double inflation);

  // Same for the linear trajectories V0 -> V1 (swept boxes): every pair that comes closer
  // than `inflation` at some t in [0, 1] is returned.
  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V0, const Eigen::MatrixXd &V1,
                                         double inflation);
} // namespace ritr::contact
