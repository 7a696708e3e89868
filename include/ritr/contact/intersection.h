#pragma once
// Exact intersection tests of a collision surface, for validating initial states: distance
// checks alone cannot see a segment crossing another segment (2D) or an edge piercing a
// triangle (3D) when no vertex is close to the other primitive.
#include <ritr/contact/collision_surface.h>

#include <Eigen/Core>

#include <array>
#include <optional>

namespace ritr::contact
{
  // True when two non-adjacent primitives (not both obstacle) intersect: in 1D a vertex
  // strictly inside another body's interval or two coincident vertices, in 2D two crossing
  // or touching segments, in 3D an edge touching a triangle. `body_of_vertex` (1D) gives
  // the interval each body vertex bounds.
  template <int dim>
  bool has_intersections(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V);

  // The first two intersecting primitives found as above, each given by one of its
  // vertices (to name what intersects), or nothing.
  template <int dim>
  std::optional<std::array<int, 2>> find_intersection(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V);
} // namespace ritr::contact
