#pragma once
// Sparse-matrix contributions as the terms and solvers pass them around: (row, column, value)
// entries, duplicates summed when the matrix is built.
#include <Eigen/SparseCore>

#include <vector>

namespace ritr
{
  using Triplets = std::vector<Eigen::Triplet<double>>;
} // namespace ritr
