#include <ritr/common/aabb_tree.h>

#include <algorithm>

namespace ritr
{
  namespace
  {
    constexpr int leaf_size = 4;
  }

  template <int dim>
  AabbTree<dim>::AabbTree(const std::vector<Aabb<dim>> &boxes_in) : boxes(boxes_in)
  {
    const int n = static_cast<int>(boxes.size());
    if (n == 0)
      return;
    order.resize(n);
    std::vector<Eigen::Matrix<double, dim, 1>> centers(n);
    for (int i = 0; i < n; ++i)
      {
        order[i]   = i;
        centers[i] = 0.5 * (boxes[i].min + boxes[i].max);
      }
    nodes.reserve(2 * (n / leaf_size + 1));
    build(0, n, centers);
  }

  template <int dim>
  int AabbTree<dim>::build(const int begin, const int end,
                           std::vector<Eigen::Matrix<double, dim, 1>> &centers)
  {
    const int index = static_cast<int>(nodes.size());
    nodes.emplace_back();
    Aabb<dim> box, center_box;
    for (int i = begin; i < end; ++i)
      {
        box.extend(boxes[order[i]]);
        center_box.min = center_box.min.cwiseMin(centers[order[i]]);
        center_box.max = center_box.max.cwiseMax(centers[order[i]]);
      }
    nodes[index].box = box;
    if (end - begin <= leaf_size)
      {
        nodes[index].begin = begin;
        nodes[index].end   = end;
        return index;
      }
    int axis;
    (center_box.max - center_box.min).maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](const int a, const int b) { return centers[a][axis] < centers[b][axis]; });
    const int left  = build(begin, mid, centers);
    const int right = build(mid, end, centers);
    nodes[index].left  = left;
    nodes[index].right = right;
    return index;
  }

  template class AabbTree<1>;
  template class AabbTree<2>;
  template class AabbTree<3>;
} // namespace ritr
