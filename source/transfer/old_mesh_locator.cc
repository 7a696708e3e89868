#include <ritr/transfer/old_mesh_locator.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace ritr::transfer
{
  template <int dim>
  OldMeshLocator<dim>::OldMeshLocator(const std::vector<Cell> &cells, const Eigen::VectorXd &u_old,
                                      const double tolerance)
    : cells_(cells), tolerance_(tolerance)
  {
    const std::size_t n_cells = cells_.size();
    nodes_.resize(n_cells * (dim + 1));
    maps_.resize(n_cells);
    std::vector<Aabb<dim>> boxes(n_cells);
    double                          diameter_sum = 0;
    for (std::size_t o = 0; o < n_cells; ++o)
      {
        Eigen::Matrix<double, dim, dim> D;
        for (int a = 0; a <= dim; ++a)
          {
            const std::size_t node = cells_[o][a];
            if ((node + 1) * dim > static_cast<std::size_t>(u_old.size()))
              throw std::invalid_argument("OldMeshLocator: cell " + std::to_string(o) +
                                          " refers to a node beyond u_old");
            nodes_[o * (dim + 1) + a] = u_old.template segment<dim>(node * dim);
          }
        const Point &p0 = nodes_[o * (dim + 1)];
        for (int a = 0; a < dim; ++a)
          D.col(a) = nodes_[o * (dim + 1) + a + 1] - p0;
        const double det = D.determinant();
        const double size = D.colwise().norm().maxCoeff();
        if (!(std::abs(det) > 1e-14 * std::pow(size, dim)))
          throw std::invalid_argument("OldMeshLocator: old cell " + std::to_string(o) +
                                      " is degenerate");
        // mu_{1..dim} = D^{-1} (X - p0), mu_0 = 1 - sum of the others.
        const Eigen::Matrix<double, dim, dim> Dinv = D.inverse();
        AffineBarycentric<dim>               &m    = maps_[o];
        m.gradient.template bottomRows<dim>()      = Dinv;
        m.gradient.row(0)                          = -Dinv.colwise().sum();
        m.offset.template tail<dim>()              = -Dinv * p0;
        m.offset[0]                                = 1.0 - m.offset.template tail<dim>().sum();

        Aabb<dim> &box = boxes[o];
        for (int a = 0; a <= dim; ++a)
          {
            box.min = box.min.cwiseMin(nodes_[o * (dim + 1) + a]);
            box.max = box.max.cwiseMax(nodes_[o * (dim + 1) + a]);
          }
        const double diameter = (box.max - box.min).norm();
        diameter_sum += diameter;
        // A point with mu_b >= -tolerance lies within tolerance * (height) of the cell.
        box.inflate(2 * tolerance_ * diameter);
      }
    tree_           = AabbTree<dim>(boxes);
    build_neighbors();
    initial_radius_ = n_cells > 0 ? diameter_sum / n_cells : 1.0;
  }

  template <int dim>
  void OldMeshLocator<dim>::build_neighbors()
  {
    // Sort (face nodes, cell, local face) records so that the two sides of a face meet.
    struct FaceRecord
    {
      std::array<unsigned int, dim> nodes;
      int                           cell;
      int                           face;
    };
    std::vector<FaceRecord> faces;
    faces.reserve(cells_.size() * (dim + 1));
    for (std::size_t o = 0; o < cells_.size(); ++o)
      for (int f = 0; f <= dim; ++f)
        {
          FaceRecord r;
          for (int a = 0, k = 0; a <= dim; ++a)
            if (a != f)
              r.nodes[k++] = cells_[o][a];
          std::sort(r.nodes.begin(), r.nodes.end());
          r.cell = static_cast<int>(o);
          r.face = f;
          faces.push_back(r);
        }
    std::sort(faces.begin(), faces.end(), [](const FaceRecord &a, const FaceRecord &b) {
      return a.nodes < b.nodes || (a.nodes == b.nodes && a.cell < b.cell);
    });
    neighbors_.assign(cells_.size(), {});
    for (auto &n : neighbors_)
      n.fill(-1);
    for (std::size_t i = 0; i + 1 < faces.size(); ++i)
      if (faces[i].nodes == faces[i + 1].nodes)
        {
          neighbors_[faces[i].cell][faces[i].face]         = faces[i + 1].cell;
          neighbors_[faces[i + 1].cell][faces[i + 1].face] = faces[i].cell;
        }
  }

  template <int dim>
  std::array<double, dim + 1> OldMeshLocator<dim>::barycentric(const int o, const Point &X) const
  {
    const AffineBarycentric<dim>         &m  = maps_[o];
    const Eigen::Matrix<double, dim + 1, 1> mu = m.gradient * X + m.offset;
    std::array<double, dim + 1>           r;
    for (int b = 0; b <= dim; ++b)
      r[b] = mu[b];
    return r;
  }

  template <int dim>
  double OldMeshLocator<dim>::distance(const int o, const Point &X) const
  {
    const auto mu = barycentric(o, X);
    if (*std::min_element(mu.begin(), mu.end()) >= 0)
      return 0.0;
    // The closest point lies in the relative interior of some face (vertex, edge, ...), where
    // it is the orthogonal projection onto that face's affine hull: try every face and keep
    // the projections that land inside their face.
    double best = std::numeric_limits<double>::infinity();
    for (unsigned int mask = 1; mask < (1u << (dim + 1)); ++mask)
      {
        int vertices[dim + 1], k = 0;
        for (int a = 0; a <= dim; ++a)
          if (mask & (1u << a))
            vertices[k++] = a;
        const Point &p0 = nodes_[o * (dim + 1) + vertices[0]];
        Point        closest = p0;
        if (k > 1)
          {
            Eigen::Matrix<double, dim, Eigen::Dynamic, 0, dim, dim> E(dim, k - 1);
            for (int j = 1; j < k; ++j)
              E.col(j - 1) = nodes_[o * (dim + 1) + vertices[j]] - p0;
            const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, dim, 1> alpha =
              (E.transpose() * E).ldlt().solve(E.transpose() * (X - p0));
            if (alpha.minCoeff() < 0 || alpha.sum() > 1)
              continue;
            closest = p0 + E * alpha;
          }
        best = std::min(best, (X - closest).norm());
      }
    return best;
  }

  template <int dim>
  Location<dim> OldMeshLocator<dim>::locate(const Point &X) const
  {
    return locate_in_tree(X, -1);
  }

  template <int dim>
  Location<dim> OldMeshLocator<dim>::locate(const Point &X, const int hint) const
  {
    if (hint < 0 || hint >= static_cast<int>(cells_.size()))
      return locate_in_tree(X, -1);
    // Walk from the hint across the face with the most negative coordinate: nearby points
    // are found in a step or two instead of a tree descent.
    int o = hint;
    for (int step = 0; step < max_walk_steps; ++step)
      {
        const auto mu     = barycentric(o, X);
        const auto lowest = std::min_element(mu.begin(), mu.end());
        if (*lowest >= interior_margin)
          {
            Location<dim> result;
            result.cell        = o;
            result.barycentric = mu;
            return result;
          }
        const int next = neighbors_[o][lowest - mu.begin()];
        if (next < 0 || *lowest >= -tolerance_)
          break; // at the boundary, or on a face (the tree resolves shared faces)
        o = next;
      }
    return locate_in_tree(X, o);
  }

  template <int dim>
  Location<dim> OldMeshLocator<dim>::locate_in_tree(const Point &X, const int hint) const
  {
    Aabb<dim> query;
    query.min = X;
    query.max = X;
    Location<dim> result;
    tree_.for_each_overlap(query, [&](const int o) {
      if (result.cell >= 0 && o > result.cell)
        return;
      const auto mu = barycentric(o, X);
      if (*std::min_element(mu.begin(), mu.end()) >= -tolerance_)
        {
          result.cell        = o;
          result.barycentric = mu;
        }
    });
    if (result.cell >= 0)
      return result;
    return search_outside(X, hint);
  }

  template <int dim>
  Location<dim> OldMeshLocator<dim>::search_outside(const Point &X, const int hint) const
  {
    if (cells_.empty())
      throw std::logic_error("OldMeshLocator: empty old mesh");
    // Grow a box around X until it holds a cell no farther than its half-width: every cell
    // at that distance or less overlaps the box, so the nearest one is among those tested.
    // Outside points are usually just outside (boundary sliding), so start from the
    // distance to the hint cell (an upper bound) or from a small fraction of a cell.
    double radius = hint >= 0 ? distance(hint, X) * (1 + 1e-9) + 1e-14 * initial_radius_ : 0.0;
    if (!(radius > 0))
      radius = 1e-3 * initial_radius_;
    for (;;)
      {
        Aabb<dim> query;
        query.min = X;
        query.max = X;
        query.inflate(radius);
        std::vector<std::pair<int, double>> found;
        double                              best = std::numeric_limits<double>::infinity();
        tree_.for_each_overlap(query, [&](const int o) {
          const double d = distance(o, X);
          found.emplace_back(o, d);
          best = std::min(best, d);
        });
        // Distances within this band of the minimum count as ties (cells sharing the closest
        // vertex or edge); the smallest index wins, whatever the traversal order or radius.
        const double tie       = 1e-10 * best + 1e-14 * initial_radius_;
        int          best_cell = -1;
        for (const auto &[o, d] : found)
          if (d <= best + tie && (best_cell < 0 || o < best_cell))
            best_cell = o;
        if (best_cell >= 0 && best + tie <= radius)
          {
            Location<dim> result;
            result.cell        = best_cell;
            result.barycentric = barycentric(best_cell, X);
            result.inside      = false;
            return result;
          }
        radius *= 2;
      }
  }

  template class OldMeshLocator<1>;
  template class OldMeshLocator<2>;
  template class OldMeshLocator<3>;
} // namespace ritr::transfer
