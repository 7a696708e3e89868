#pragma once
// Inside tests for validating initial states: a body, or an obstacle, wholly inside another
// closed component crosses no boundary, so intersection tests cannot see it. A closed
// component is a set of facets -- 2D segments, 3D triangles -- that bounds a region: every
// vertex (2D) or edge (3D) is shared by an even number of its facets.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace ritr::contact
{
  // Whether `facets` (vertex indices; segments in 2D, triangles in 3D) bound a region.
  template <int dim>
  bool is_closed(const std::vector<std::array<int, dim>> &facets);

  // Whether `point` lies inside the region bounded by the closed `facets` of the vertices V
  // (rows), by the parity of a ray's crossings with them. The ray's direction changes until
  // it passes no facet's edge or vertex. A point on a facet counts as either.
  template <int dim>
  bool encloses(const Eigen::MatrixXd &V, const std::vector<std::array<int, dim>> &facets,
                const Eigen::Matrix<double, dim, 1> &point);
} // namespace ritr::contact
