#include <ritr/contact/broad_phase.h>
#include <ritr/contact/intersection.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <map>

namespace ritr::contact
{
  namespace
  {
    double orient2d(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c)
    {
      return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    }

    // Closed segments ab and cd intersect (touching counts).
    bool segments_intersect(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c,
                            const Eigen::Vector2d &d)
    {
      const double d1 = orient2d(a, b, c), d2 = orient2d(a, b, d), d3 = orient2d(c, d, a), d4 = orient2d(c, d, b);
      if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
      const auto on_segment = [](const Eigen::Vector2d &p, const Eigen::Vector2d &q, const Eigen::Vector2d &r) {
        return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) && std::min(p[1], q[1]) <= r[1] &&
               r[1] <= std::max(p[1], q[1]);
      };
      return (d1 == 0 && on_segment(a, b, c)) || (d2 == 0 && on_segment(a, b, d)) ||
             (d3 == 0 && on_segment(c, d, a)) || (d4 == 0 && on_segment(c, d, b));
    }

    // Segment pq touches triangle abc (Moller-Trumbore on the segment's parameter range).
    bool segment_triangle_intersect(const Eigen::Vector3d &p, const Eigen::Vector3d &q, const Eigen::Vector3d &a,
                                    const Eigen::Vector3d &b, const Eigen::Vector3d &c)
    {
      const Eigen::Vector3d dir = q - p, e1 = b - a, e2 = c - a;
      const Eigen::Vector3d h   = dir.cross(e2);
      const double          det = e1.dot(h);
      const double          scale = e1.norm() * e2.norm() * dir.norm();
      if (std::abs(det) <= 1e-14 * scale)
        return false;  // parallel: a coplanar crossing also crosses a neighbouring triangle's edge
      const Eigen::Vector3d s = p - a;
      const double          u = s.dot(h) / det;
      if (u < 0 || u > 1)
        return false;
      const Eigen::Vector3d qv = s.cross(e1);
      const double          v  = dir.dot(qv) / det;
      if (v < 0 || u + v > 1)
        return false;
      const double t = e2.dot(qv) / det;
      return t >= 0 && t <= 1;
    }

    template <int dim>
    Aabb<dim> box_of(const Eigen::MatrixXd &V, std::initializer_list<int> vertices)
    {
      Aabb<dim> box;
      for (const int v : vertices)
        {
          const Eigen::Matrix<double, dim, 1> p = V.row(v).transpose();
          box.min                               = box.min.cwiseMin(p);
          box.max                               = box.max.cwiseMax(p);
        }
      return box;
    }
  } // namespace

  template <int dim>
  std::optional<std::array<int, 2>> find_intersection(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V)
  {
    if constexpr (dim == 1)
      {
        // Body intervals from their vertices (and one vertex of each, to name it); obstacle
        // points and other bodies must stay outside.
        struct Interval
        {
          double lower, upper;
          int    vertex;
        };
        std::map<int, Interval> interval;
        for (int v = 0; v < surface.n_vertices; ++v)
          if (!surface.vertex_is_obstacle(v))
            {
              auto it = interval.emplace(surface.body_id[v], Interval{V(v, 0), V(v, 0), v}).first;
              it->second.lower = std::min(it->second.lower, V(v, 0));
              it->second.upper = std::max(it->second.upper, V(v, 0));
            }
        for (int v = 0; v < surface.n_vertices; ++v)
          for (const auto &[body, range] : interval)
            if ((surface.vertex_is_obstacle(v) || surface.body_id[v] != body) && range.lower <= V(v, 0) &&
                V(v, 0) <= range.upper)
              return std::array<int, 2>{v, range.vertex};
        return std::nullopt;
      }
    else
      {
        // Tree over segments (2D) or triangles (3D); every edge queries it.
        std::vector<Aabb<dim>> boxes;
        if constexpr (dim == 2)
          for (const auto &e : surface.edges)
            boxes.push_back(box_of<dim>(V, {e[0], e[1]}));
        else
          for (const auto &f : surface.faces)
            boxes.push_back(box_of<dim>(V, {f[0], f[1], f[2]}));
        const AabbTree<dim> tree(boxes);
        for (std::size_t e = 0; e < surface.edges.size(); ++e)
          {
            const auto &edge  = surface.edges[e];
            int         found = -1;  // the primitive the edge meets
            tree.for_each_overlap(box_of<dim>(V, {edge[0], edge[1]}), [&](const int other) {
              if (found >= 0)
                return;
              if constexpr (dim == 2)
                {
                  const auto &o = surface.edges[other];
                  if (static_cast<int>(e) >= other || o[0] == edge[0] || o[0] == edge[1] || o[1] == edge[0] ||
                      o[1] == edge[1] || (surface.edge_is_obstacle(e) && surface.edge_is_obstacle(other)))
                    return;
                  if (segments_intersect(V.row(edge[0]).transpose(), V.row(edge[1]).transpose(),
                                         V.row(o[0]).transpose(), V.row(o[1]).transpose()))
                    found = o[0];
                }
              else
                {
                  const auto &f = surface.faces[other];
                  for (const int v : f)
                    if (v == edge[0] || v == edge[1])
                      return;
                  if (surface.edge_is_obstacle(e) && surface.face_is_obstacle(other))
                    return;
                  if (segment_triangle_intersect(V.row(edge[0]).transpose(), V.row(edge[1]).transpose(),
                                                 V.row(f[0]).transpose(), V.row(f[1]).transpose(),
                                                 V.row(f[2]).transpose()))
                    found = f[0];
                }
            });
            if (found >= 0)
              return std::array<int, 2>{edge[0], found};
          }
        return std::nullopt;
      }
  }

  template <int dim>
  bool has_intersections(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V)
  {
    return find_intersection<dim>(surface, V).has_value();
  }

  template std::optional<std::array<int, 2>> find_intersection<1>(const CollisionSurface<1> &, const Eigen::MatrixXd &);
  template std::optional<std::array<int, 2>> find_intersection<2>(const CollisionSurface<2> &, const Eigen::MatrixXd &);
  template std::optional<std::array<int, 2>> find_intersection<3>(const CollisionSurface<3> &, const Eigen::MatrixXd &);
  template bool has_intersections<1>(const CollisionSurface<1> &, const Eigen::MatrixXd &);
  template bool has_intersections<2>(const CollisionSurface<2> &, const Eigen::MatrixXd &);
  template bool has_intersections<3>(const CollisionSurface<3> &, const Eigen::MatrixXd &);
} // namespace ritr::contact
