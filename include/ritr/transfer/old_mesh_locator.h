#pragma once
// Point location in the start-of-step ("old") mesh, built once per time step.
//
// Every quadrature point of every candidate mesh the r-ITR optimiser tries is looked up
// here, so the per-cell affine barycentric maps are precomputed: mu(X) = G X + g. The
// transfer derivatives use that the map is affine for a fixed old cell.
#include <ritr/common/aabb_tree.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ritr::transfer
{
  // Barycentric coordinates of X in old cell `cell`: mu = gradient * X + offset.
  template <int dim>
  struct AffineBarycentric
  {
    Eigen::Matrix<double, dim + 1, dim, Eigen::DontAlign> gradient;
    Eigen::Matrix<double, dim + 1, 1, Eigen::DontAlign>   offset;
  };

  template <int dim>
  struct Location
  {
    int                         cell = -1; // old cell index
    std::array<double, dim + 1> barycentric{};
    // False when X lies outside the old domain (beyond the tolerance); `barycentric` then
    // belongs to the linear extension of the nearest old cell and has negative entries.
    bool inside = true;
  };

  template <int dim>
  class OldMeshLocator
  {
  public:
    using Cell  = std::array<unsigned int, dim + 1>;
    using Point = Eigen::Matrix<double, dim, 1>;

    OldMeshLocator() = default;

    // `tolerance` is on barycentric coordinates: X is in cell o when min_b mu_b >= -tolerance.
    // Cells must be non-degenerate at u_old (throws std::invalid_argument otherwise).
    OldMeshLocator(const std::vector<Cell> &cells, const Eigen::VectorXd &u_old,
                   double tolerance = 1e-12);

    // The containing cell with the smallest index (so that points on shared faces resolve
    // deterministically), or, outside the domain, the nearest cell (Euclidean distance;
    // ties to the smallest index).
    Location<dim> locate(const Point &X) const;

    // Same result, found faster for X near `hint` (e.g. the cell of a nearby point): walks
    // from the hint through face neighbours and accepts a cell without a tree search when X
    // is inside it by a margin (min mu >= interior_margin), where no other cell can contain
    // X unless neighbouring cells differ in size by ~1/interior_margin. Points near faces,
    // outside the domain or far away fall back to the tree.
    Location<dim> locate(const Point &X, int hint) const;

    // Barycentric coordinates of X with respect to old cell o (its linear extension).
    std::array<double, dim + 1> barycentric(int o, const Point &X) const;

    // Calls f(o) for every old cell whose bounding box overlaps `box`.
    template <typename F>
    void for_each_cell_near(const Aabb<dim> &box, F &&f) const
    {
      tree_.for_each_overlap(box, f);
    }

    // Euclidean distance from X to old cell o (zero inside).
    double distance(int o, const Point &X) const;

    const AffineBarycentric<dim> &affine_map(const int o) const { return maps_[o]; }
    const Cell                   &cell(const int o) const { return cells_[o]; }
    const Point                  &node(const int o, const int a) const { return nodes_[o * (dim + 1) + a]; }
    unsigned int                  n_cells() const { return cells_.size(); }
    double                        tolerance() const { return tolerance_; }

    // Old cell across the face opposite local node f, or -1 on the boundary.
    int neighbor(const int o, const int f) const { return neighbors_[o][f]; }

    static constexpr double interior_margin = 1e-6;
    static constexpr int    max_walk_steps  = 8;

  private:
    void          build_neighbors();
    Location<dim> locate_in_tree(const Point &X, int hint) const;
    Location<dim> search_outside(const Point &X, int hint) const;

    std::vector<Cell>                   cells_;
    std::vector<Point, Eigen::aligned_allocator<Point>> nodes_; // cell-major: o*(dim+1) + a
    std::vector<AffineBarycentric<dim>> maps_;
    std::vector<std::array<int, dim + 1>> neighbors_;
    AabbTree<dim>              tree_;
    double                              tolerance_      = 1e-12;
    double                              initial_radius_ = 1; // mean cell box diagonal
  };
} // namespace ritr::transfer
