#include <ritr/contact/rigid_obstacle.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>

namespace ritr::contact
{
  template <int dim>
  std::vector<typename RigidObstacle<dim>::Point> RigidObstacle<dim>::vertices_at(const double t) const
  {
    std::vector<Point> v = rest_vertices;
    const double       a = angle ? angle(t) : 0.0;
    if (a != 0.0)
      {
        if constexpr (dim == 2)
          {
            const Eigen::Rotation2Dd r(a);
            for (auto &p : v)
              p = r * (p - center) + center;
          }
        else if constexpr (dim == 3)
          {
            const Eigen::AngleAxisd r(a, axis.normalized());
            for (auto &p : v)
              p = r * (p - center) + center;
          }
      }
    if (translation)
      {
        const Point shift = translation(t);
        for (auto &p : v)
          p += shift;
      }
    return v;
  }

  template <int dim>
  RigidObstacle<dim> make_plane(const Eigen::Matrix<double, dim, 1> &point,
                                const Eigen::Matrix<double, dim, 1> &normal, const double extent)
  {
    RigidObstacle<dim> o;
    o.center = point;
    if constexpr (dim == 1)
      o.rest_vertices = {point};
    else if constexpr (dim == 2)
      {
        const Eigen::Vector2d t(-normal[1], normal[0]);
        const Eigen::Vector2d d = 0.5 * extent * t.normalized();
        o.rest_vertices         = {point - d, point + d};
        o.edges                 = {{0, 1}};
      }
    else
      {
        const Eigen::Vector3d n = normal.normalized();
        const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
        const double          h = 0.5 * extent;
        o.rest_vertices = {point - h * a - h * b, point + h * a - h * b, point + h * a + h * b,
                           point - h * a + h * b};
        o.faces         = {{0, 1, 2}, {0, 2, 3}};
      }
    return o;
  }

  template <int dim>
  RigidObstacle<dim> make_box(const Eigen::Matrix<double, dim, 1> &center,
                              const Eigen::Matrix<double, dim, 1> &size)
  {
    RigidObstacle<dim> o;
    o.center = center;
    if constexpr (dim == 1)
      throw std::runtime_error("boxes do not exist in 1D");
    else if constexpr (dim == 2)
      {
        const Eigen::Vector2d h = 0.5 * size;
        o.rest_vertices = {center + Eigen::Vector2d(-h[0], -h[1]), center + Eigen::Vector2d(h[0], -h[1]),
                           center + Eigen::Vector2d(h[0], h[1]), center + Eigen::Vector2d(-h[0], h[1])};
        o.edges         = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
      }
    else
      {
        for (int i = 0; i < 8; ++i)
          o.rest_vertices.push_back(center + 0.5 * Eigen::Vector3d((i & 1) ? size[0] : -size[0],
                                                                   (i & 2) ? size[1] : -size[1],
                                                                   (i & 4) ? size[2] : -size[2]));
        // Two outward triangles per face of the cube (vertex bit k = coordinate k).
        o.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
      }
    return o;
  }

  template <int dim>
  RigidObstacle<dim> make_spikes(const Eigen::Matrix<double, dim, 1> &base_center, const double length,
                                 const unsigned int count, const double height)
  {
    RigidObstacle<dim> o;
    o.center          = base_center;
    const double step = length / count;
    if constexpr (dim == 1)
      throw std::runtime_error("spikes do not exist in 1D");
    else if constexpr (dim == 2)
      {
        // Zig-zag polyline: base, tip, base, ..., base.
        const double x0 = base_center[0] - 0.5 * length;
        for (unsigned int i = 0; i <= count; ++i)
          {
            o.rest_vertices.push_back(Eigen::Vector2d(x0 + i * step, base_center[1]));
            if (i < count)
              o.rest_vertices.push_back(Eigen::Vector2d(x0 + (i + 0.5) * step, base_center[1] + height));
          }
        for (unsigned int i = 0; i + 1 < o.rest_vertices.size(); ++i)
          o.edges.push_back({static_cast<int>(i), static_cast<int>(i + 1)});
      }
    else
      {
        // Grid of square pyramids on the plane y = base: (count+1)^2 base nodes, count^2 tips.
        const double x0 = base_center[0] - 0.5 * length, z0 = base_center[2] - 0.5 * length;
        const auto   base = [&](unsigned int i, unsigned int k) { return static_cast<int>(i * (count + 1) + k); };
        for (unsigned int i = 0; i <= count; ++i)
          for (unsigned int k = 0; k <= count; ++k)
            o.rest_vertices.push_back(Eigen::Vector3d(x0 + i * step, base_center[1], z0 + k * step));
        for (unsigned int i = 0; i < count; ++i)
          for (unsigned int k = 0; k < count; ++k)
            {
              const int tip = static_cast<int>(o.rest_vertices.size());
              o.rest_vertices.push_back(
                Eigen::Vector3d(x0 + (i + 0.5) * step, base_center[1] + height, z0 + (k + 0.5) * step));
              const int a = base(i, k), b = base(i + 1, k), c = base(i + 1, k + 1), d = base(i, k + 1);
              o.faces.push_back({a, tip, b});
              o.faces.push_back({b, tip, c});
              o.faces.push_back({c, tip, d});
              o.faces.push_back({d, tip, a});
            }
      }
    return o;
  }

  template <int dim>
  int first_degenerate_element(const RigidObstacle<dim> &obstacle)
  {
    constexpr double degenerate = 1e-12;
    const auto      &p          = obstacle.rest_vertices;
    if (p.empty())
      return -1;
    Eigen::Matrix<double, dim, 1> lower = p.front(), upper = p.front();
    for (const auto &v : p)
      {
        lower = lower.cwiseMin(v);
        upper = upper.cwiseMax(v);
      }
    const double shortest = degenerate * (upper - lower).norm();
    if constexpr (dim == 2)
      for (std::size_t e = 0; e < obstacle.edges.size(); ++e)
        if (!((p[obstacle.edges[e][1]] - p[obstacle.edges[e][0]]).norm() > shortest))
          return static_cast<int>(e);
    if constexpr (dim == 3)
      for (std::size_t f = 0; f < obstacle.faces.size(); ++f)
        {
          const auto  &a = p[obstacle.faces[f][0]], &b = p[obstacle.faces[f][1]], &c = p[obstacle.faces[f][2]];
          const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
          if (!(longest > shortest) || !((b - a).cross(c - a).norm() > degenerate * longest * longest))
            return static_cast<int>(f);
        }
    return -1;
  }

#define RITR_INSTANTIATE(dim)                                                                          \
  template struct RigidObstacle<dim>;                                                                  \
  template RigidObstacle<dim> make_plane<dim>(const Eigen::Matrix<double, dim, 1> &,                   \
                                              const Eigen::Matrix<double, dim, 1> &, double);          \
  template RigidObstacle<dim> make_box<dim>(const Eigen::Matrix<double, dim, 1> &,                     \
                                            const Eigen::Matrix<double, dim, 1> &);                    \
  template RigidObstacle<dim> make_spikes<dim>(const Eigen::Matrix<double, dim, 1> &, double,          \
                                               unsigned int, double);                                  \
  template int                first_degenerate_element<dim>(const RigidObstacle<dim> &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
