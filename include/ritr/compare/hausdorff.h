#pragma once
// Hausdorff distance between two deformed boundaries (polylines in 2D, triangle surfaces in 3D,
// end points in 1D).
#include <ritr/compare/boundary.h>

namespace ritr::compare
{
  // sup over points p of `from` of the distance from p to `to` (not symmetric). Exact for 1D;
  // in 2D and 3D a sampled lower bound refined until it settles, see hausdorff.cc.
  double one_sided_distance(const Boundary &from, const Boundary &to);

  // max(one_sided_distance(a, b), one_sided_distance(b, a)).
  double hausdorff_distance(const Boundary &a, const Boundary &b);
} // namespace ritr::compare
