#pragma once
// Broad phase: candidate primitive pairs whose (inflated) axis-aligned bounding boxes
// overlap, found with a median-split AABB tree (O(n log n) build, O(log n + k) per query)
// and TBB-parallel queries.
#include <ritr/contact/collision_surface.h>

#include <Eigen/Core>

#include <array>
#include <limits>
#include <tuple>
#include <vector>

namespace ritr::contact
{
  template <int dim>
  struct Aabb
  {
    Eigen::Matrix<double, dim, 1> min = Eigen::Matrix<double, dim, 1>::Constant(
      std::numeric_limits<double>::infinity());
    Eigen::Matrix<double, dim, 1> max = Eigen::Matrix<double, dim, 1>::Constant(
      -std::numeric_limits<double>::infinity());

    void extend(const Aabb &b)
    {
      min = min.cwiseMin(b.min);
      max = max.cwiseMax(b.max);
    }
    void inflate(const double r)
    {
      min.array() -= r;
      max.array() += r;
    }
    bool overlaps(const Aabb &b) const
    {
      return (min.array() <= b.max.array()).all() && (b.min.array() <= max.array()).all();
    }
  };

  // Static bounding-volume hierarchy over a fixed set of boxes.
  template <int dim>
  class AabbTree
  {
  public:
    AabbTree() = default;
    explicit AabbTree(const std::vector<Aabb<dim>> &boxes);

    // Calls f(id) for every stored box overlapping `query`.
    template <typename Callback>
    void for_each_overlap(const Aabb<dim> &query, Callback &&f) const
    {
      if (nodes.empty())
        return;
      // Median splits bound the depth by log2(n) + 1, so a fixed stack suffices.
      int stack[128];
      int top      = 0;
      stack[top++] = 0;
      while (top > 0)
        {
          const Node &node = nodes[stack[--top]];
          if (!node.box.overlaps(query))
            continue;
          if (node.left < 0)
            {
              for (int i = node.begin; i < node.end; ++i)
                if (boxes[order[i]].overlaps(query))
                  f(order[i]);
            }
          else
            {
              stack[top++] = node.left;
              stack[top++] = node.right;
            }
        }
    }

    std::size_t size() const { return boxes.size(); }

  private:
    struct Node
    {
      Aabb<dim> box;
      int       left  = -1; // child indices, -1 for a leaf
      int       right = -1;
      int       begin = 0; // leaf range in `order`
      int       end   = 0;
    };
    int build(int begin, int end, std::vector<Eigen::Matrix<double, dim, 1>> &centers);

    std::vector<Aabb<dim>> boxes;
    std::vector<int>       order;
    std::vector<Node>      nodes;
  };

  // A candidate primitive pair.
  //  vertex_vertex:  first, second = vertices
  //  point_edge:     first = vertex, second = edge
  //  point_triangle: first = vertex, second = face
  //  edge_edge:      first, second = edges
  // For the symmetric kinds (vertex_vertex, edge_edge) `first` is a body primitive when
  // exactly one of the two is an obstacle, otherwise the smaller index; the constraint
  // weight is that of `first`.
  struct Candidate
  {
    ContactKind kind   = ContactKind::vertex_vertex;
    int         first  = -1;
    int         second = -1;

    bool operator<(const Candidate &o) const
    {
      return std::tie(kind, first, second) < std::tie(o.kind, o.first, o.second);
    }
    bool operator==(const Candidate &o) const
    {
      return kind == o.kind && first == o.first && second == o.second;
    }
  };

  // The stencil vertices of a candidate (ordering as in distance.h) and their count.
  template <int dim>
  int stencil_vertices(const CollisionSurface<dim> &surface, const Candidate &c,
                       std::array<int, 4> &vertices);

  // All candidate pairs (not sharing a vertex, not obstacle-obstacle) that may be closer
  // than `inflation` at positions V: every pair at distance < inflation is returned.
  // Sorted, without duplicates.
  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V, double inflation);

  // Same for the linear trajectories V0 -> V1 (swept boxes): every pair that comes closer
  // than `inflation` at some t in [0, 1] is returned.
  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V0, const Eigen::MatrixXd &V1,
                                         double inflation);
} // namespace ritr::contact
