#pragma once
// The deformed boundary of a simplex mesh: the facets that belong to exactly one cell.
#include <ritr/compare/deformed_mesh.h>

#include <vector>

namespace ritr::compare
{
  struct Boundary
  {
    // Facets have dim vertices: end points (1D), edges (2D) or triangles (3D) of the mesh.
    unsigned int                           dim = 0;
    std::vector<Point>                     points; // all points of the mesh; facets index them
    std::vector<std::vector<unsigned int>> facets;
  };

  // Every facet used by exactly one cell. Shared facets cancel pairwise, which also makes the
  // interface between two bodies that share nodes interior, as it is for the simulation.
  Boundary extract_boundary(const DeformedMesh &mesh);
} // namespace ritr::compare
