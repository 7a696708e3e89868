#pragma once
// A sparse matrix under assembly from the terms of a sum: one dense block per mesh cell,
// which every cell term adds into (so that inertia and elasticity together make one block
// per cell, as a single kernel would), and free triplets for stencils that are not cells
// (contact pairs, the L2 transfer's blocks). append_to() writes the cell blocks in cell
// order, row by row, and then the free triplets; rows and columns of a cell block are the
// cell's nodes' entries (node i, component k at i * dim + k), in either numbering a block is
// used with (state and reference numbering agree on the body nodes).
#include <ritr/common/triplets.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ritr
{
  template <int dim>
  class MatrixAssembly
  {
  public:
    static constexpr int cell_dofs = dim * (dim + 1);
    using Cell  = std::array<unsigned int, dim + 1>;
    using Block = Eigen::Map<Eigen::Matrix<double, cell_dofs, cell_dofs>>;

    // The cells must outlive the assembly.
    explicit MatrixAssembly(const std::vector<Cell> &cells) : cells_(&cells) {}

    // The blocks of all cells, zero until terms add to them. Allocated here, so a parallel
    // loop over cells calls this once before it starts.
    void use_cell_blocks()
    {
      if (values_.empty())
        values_.assign(cells_->size() * cell_dofs * cell_dofs, 0.0);
    }
    Block cell_block(const std::size_t c) { return Block(values_.data() + c * cell_dofs * cell_dofs); }

    const std::vector<Cell> &cells() const { return *cells_; }

    Triplets       &triplets() { return triplets_; }
    const Triplets &triplets() const { return triplets_; }

    // One cell's block (column-major, cell_dofs^2 values) appended as triplets, in the order
    // append_to() writes a cell block.
    static void append_block(const Cell &cell, const double *block, Eigen::Triplet<double> *out);

    // Forgets every contribution; the storage stays for the next assembly.
    void clear();
    // Appends everything as triplets: cell blocks first (in parallel), then the free ones.
    void append_to(Triplets &out) const;
    Triplets to_triplets() const
    {
      Triplets t;
      append_to(t);
      return t;
    }

  private:
    const std::vector<Cell> *cells_;
    std::vector<double>      values_;  // cell_dofs^2 per cell, column-major blocks
    Triplets                 triplets_;
  };
} // namespace ritr
