#include <ritr/compare/hausdorff.h>
#include <ritr/common/input_error.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace ritr::compare
{
  namespace
  {
    using Kernel   = CGAL::Simple_cartesian<double>;
    using Point_3  = Kernel::Point_3;
    using Segment  = Kernel::Segment_3;
    using Triangle = Kernel::Triangle_3;

    // Sampling rule of the one-sided distance: the samples are every facet's barycentric lattice
    // with n subdivisions per edge (its vertices, n - 1 points inside each edge, and in 3D the
    // interior lattice points), n = 1, 2, 4, ... The lattices are nested, so the estimate never
    // decreases; stop once doubling n changes it by less than 1 % (relative), or at the cap.
    // Each sample's distance to the other boundary is exact (CGAL AABB tree over its facets).
    constexpr double       relative_tolerance  = 0.01;
    constexpr unsigned int max_subdivisions_2d = 256;
    constexpr unsigned int max_subdivisions_3d = 32;

    Point_3 to_cgal(const Point &p)
    {
      return {p[0], p[1], p[2]};
    }

    // Lattice points p0 + (i/n)(p1 - p0) + (j/n)(p2 - p0), i + j <= n, of one segment (j = 0)
    // or triangle facet.
    template <typename Visitor>
    void visit_lattice(const Boundary &boundary, const std::vector<unsigned int> &facet, const unsigned int n,
                       const Visitor &visit)
    {
      const auto       vertex   = [&](const std::size_t k) { return to_cgal(boundary.points[facet[k]]); };
      const bool       triangle = facet.size() == 3;
      const Point_3    p0       = vertex(0);
      const Kernel::Vector_3 e1 = vertex(1) - p0;
      const Kernel::Vector_3 e2 = triangle ? vertex(2) - p0 : CGAL::NULL_VECTOR;
      for (unsigned int i = 0; i <= n; ++i)
        for (unsigned int j = 0; j <= (triangle ? n - i : 0); ++j)
          visit(p0 + (double(i) / n) * e1 + (double(j) / n) * e2);
    }

    // Exact distance from any point to the facets of one boundary: an AABB tree over its
    // segments (2D) or triangles (3D).
    template <typename Shape>
    class FacetTree
    {
      using Primitive = std::conditional_t<std::is_same_v<Shape, Segment>,
                                           CGAL::AABB_segment_primitive<Kernel, typename std::vector<Shape>::const_iterator>,
                                           CGAL::AABB_triangle_primitive<Kernel, typename std::vector<Shape>::const_iterator>>;
      using Tree      = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

    public:
      explicit FacetTree(const Boundary &boundary)
      {
        for (const auto &f : boundary.facets)
          {
            if constexpr (std::is_same_v<Shape, Segment>)
              shapes_.emplace_back(to_cgal(boundary.points[f[0]]), to_cgal(boundary.points[f[1]]));
            else
              shapes_.emplace_back(to_cgal(boundary.points[f[0]]), to_cgal(boundary.points[f[1]]),
                                   to_cgal(boundary.points[f[2]]));
          }
        tree_.insert(shapes_.cbegin(), shapes_.cend());
        tree_.accelerate_distance_queries();
      }

      double distance(const Point_3 &p) const
      {
        return std::sqrt(tree_.squared_distance(p));
      }

    private:
      std::vector<Shape> shapes_; // the tree's primitives point into this
      Tree               tree_;
    };

    template <typename Shape>
    double sampled_one_sided_distance(const Boundary &from, const Boundary &to, const unsigned int max_subdivisions)
    {
      const FacetTree<Shape> tree(to);
      const auto             at_subdivisions = [&](const unsigned int n) {
        double d = 0.0;
        for (const auto &f : from.facets)
          visit_lattice(from, f, n, [&](const Point_3 &p) { d = std::max(d, tree.distance(p)); });
        return d;
      };
      double d = at_subdivisions(1);
      for (unsigned int n = 2; n <= max_subdivisions; n *= 2)
        {
          const double refined = at_subdivisions(n);
          const bool   settled = refined - d <= relative_tolerance * refined;
          d                    = refined;
          if (settled)
            break;
        }
      return d;
    }

    // 1D: the boundaries are finite point sets, so the distance is exact.
    double point_set_distance(const Boundary &from, const Boundary &to)
    {
      double d = 0.0;
      for (const auto &f : from.facets)
        {
          double nearest = std::numeric_limits<double>::infinity();
          for (const auto &g : to.facets)
            nearest = std::min(nearest, distance(from.points[f[0]], to.points[g[0]]));
          d = std::max(d, nearest);
        }
      return d;
    }
  } // namespace

  double one_sided_distance(const Boundary &from, const Boundary &to)
  {
    if (from.dim != to.dim)
      throw InputError("cannot compare a " + std::to_string(from.dim) + "D mesh with a " + std::to_string(to.dim) +
                       "D mesh");
    if (from.facets.empty() || to.facets.empty())
      throw InputError("cannot compare an empty boundary");
    switch (from.dim)
      {
        case 1: return point_set_distance(from, to);
        case 2: return sampled_one_sided_distance<Segment>(from, to, max_subdivisions_2d);
        default: return sampled_one_sided_distance<Triangle>(from, to, max_subdivisions_3d);
      }
  }

  double hausdorff_distance(const Boundary &a, const Boundary &b)
  {
    return std::max(one_sided_distance(a, b), one_sided_distance(b, a));
  }
} // namespace ritr::compare
