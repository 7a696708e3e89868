#pragma once
// One output frame of a run as ritr-compare sees it: the deformed simplices and nothing else.
// Plain arrays, no deal.II and no VTK, so that the geometry and its tests build in seconds.
#include <array>
#include <vector>

namespace ritr::compare
{
  // Points always carry three coordinates; 1D and 2D meshes have zero trailing coordinates.
  using Point = std::array<double, 3>;

  struct DeformedMesh
  {
    unsigned int                           dim = 0; // 1 lines, 2 triangles, 3 tetrahedra
    std::vector<Point>                     points;  // deformed positions
    std::vector<std::vector<unsigned int>> cells;   // dim + 1 point indices each
  };

  double distance(const Point &a, const Point &b);

  // Measure-weighted mean of the cell centroids (length in 1D, area in 2D, volume in 3D): the
  // centre of mass of the deformed body at uniform density. Unlike the mean of the boundary
  // vertices it does not move when r-adaptivity gathers nodes somewhere, so runs on different
  // meshes are compared fairly.
  Point centroid(const DeformedMesh &mesh);
} // namespace ritr::compare
