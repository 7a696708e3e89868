#pragma once
// A sparse matrix under assembly from the terms of a sum: one dense block per mesh cell,
// which every cell term adds into (so that inertia and elasticity together make one block
// per cell, as a single kernel would), and free triplets for stencils that are not cells
// (contact pairs, the L2 transfer's blocks). append_to() writes the cell blocks in cell
// order, row by row, and then the free triplets; rows and columns of a cell block are the
// cell's nodes' entries (node i, component k at i * dim + k), in either numbering a block is
// used with (state and reference numbering agree on the body nodes).
//
// Beside the matrix, an assembly can carry changes to it in the same layout -- a block per
// changed cell, a value per changed free triplet -- which the trust-region Newton uses for
// the projected Hessian: the exact one plus the projection's changes (energy_term.h).
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

    // The change of cell c's block (zero until added to); allocated with use_change_blocks(),
    // which a parallel loop calls once before it starts.
    void use_change_blocks();
    Block change_block(const std::size_t c)
    {
      changed_[c] = 1;
      return Block(changes_.data() + c * cell_dofs * cell_dofs);
    }
    // Free triplets [first, first + before.size()) were appended as `before` (times scale);
    // records `after` - `before` (times scale) where they differ.
    void change_triplets(std::size_t first, const Triplets &before, const Triplets &after, double scale);
    // Both of the above from one term assembled alone before and after a change, its free
    // triplets appended here from position `first` on.
    void change_by(const MatrixAssembly &before, const MatrixAssembly &after, std::size_t first);

    // Forgets every contribution and change; the storage stays for the next assembly.
    void clear();
    // Appends everything as triplets: cell blocks first (in parallel), then the free ones.
    void append_to(Triplets &out) const;
    // The changes as positions in the list that append_to() wrote from position `offset` on.
    void append_changes(std::size_t offset, TripletChanges &out) const;
    Triplets to_triplets() const
    {
      Triplets t;
      append_to(t);
      return t;
    }

  private:
    // One cell's block (column-major) as triplets, in the order append_to() writes them.
    static void append_block(const Cell &cell, const double *block, Eigen::Triplet<double> *out);

    const std::vector<Cell> *cells_;
    std::vector<double>      values_;  // cell_dofs^2 per cell, column-major blocks
    Triplets                 triplets_;
    std::vector<double>      changes_;  // as values_, zero outside the changed cells
    std::vector<char>        changed_;  // per cell
    TripletChanges           triplet_changes_;  // positions in triplets_
  };
} // namespace ritr
