#pragma once
// Axis-aligned bounding boxes and a median-split bounding-volume hierarchy over them
// (O(n log n) build, O(log n + k) per query): the contact broad phase and the transfer's
// old-mesh locator both search with it.
#include <Eigen/Core>

#include <limits>
#include <vector>

namespace ritr
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

} // namespace ritr
