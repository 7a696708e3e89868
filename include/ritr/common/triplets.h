#pragma once
// Sparse-matrix contributions as the terms and solvers pass them around: (row, column, value)
// entries, duplicates summed when the matrix is built.
#include <Eigen/SparseCore>

#include <utility>
#include <vector>

namespace ritr
{
  using Triplets = std::vector<Eigen::Triplet<double>>;

  // Changes to the values of a triplet list that keep its structure: (position of a triplet
  // in the list, value added to it). The projected Hessian is the exact one's list with the
  // projection's changes, which touch only the stencils it alters.
  using TripletChanges = std::vector<std::pair<std::size_t, double>>;
} // namespace ritr
