#include <ritr/contact/rigid_obstacle.h>

#include <Eigen/Geometry>

#include <fstream>
#include <sstream>
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
  RigidObstacle<dim> read_obj(const std::string &file)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error("cannot open obstacle file '" + file + "'");
    RigidObstacle<dim> o;
    std::string        line;
    for (unsigned int number = 1; std::getline(in, line); ++number)
      {
        std::istringstream ss(line);
        std::string        tag;
        ss >> tag;
        const auto bad = [&](const std::string &what) {
          throw std::runtime_error(file + ":" + std::to_string(number) + ": " + what);
        };
        // Face entries may be "i/t/n"; only the vertex index counts.
        const auto read_index = [&](int n_vertices) {
          std::string token;
          if (!(ss >> token))
            bad("missing vertex index");
          const int i = std::stoi(token.substr(0, token.find('/')));
          if (i < 1 || i > n_vertices)
            bad("vertex index out of range");
          return i - 1;
        };
        if (tag == "v")
          {
            double c[3] = {0, 0, 0};
            if (!(ss >> c[0] >> c[1]))
              bad("a vertex needs at least two coordinates");
            ss >> c[2];
            Eigen::Matrix<double, dim, 1> p;
            for (int k = 0; k < dim; ++k)
              p[k] = c[k];
            o.rest_vertices.push_back(p);
          }
        else if (tag == "f" && dim == 3)
          {
            const int n = o.rest_vertices.size();
            std::array<int, 3> f{read_index(n), read_index(n), read_index(n)};
            o.faces.push_back(f);
          }
        else if (tag == "l" && dim == 2)
          {
            const int n = o.rest_vertices.size();
            int       prev = read_index(n);
            std::string rest;
            while (ss >> std::ws && !ss.eof())
              {
                const int next = read_index(n);
                o.edges.push_back({prev, next});
                prev = next;
              }
          }
      }
    if (o.rest_vertices.empty() || (dim == 2 && o.edges.empty()) || (dim == 3 && o.faces.empty()))
      throw std::runtime_error("obstacle file '" + file + "' has no " +
                               (dim == 2 ? "segments ('l' lines)" : "triangles ('f' lines)"));
    return o;
  }

#define RITR_INSTANTIATE(dim)                                                                          \
  template struct RigidObstacle<dim>;                                                                  \
  template RigidObstacle<dim> make_plane<dim>(const Eigen::Matrix<double, dim, 1> &,                   \
                                              const Eigen::Matrix<double, dim, 1> &, double);          \
  template RigidObstacle<dim> make_box<dim>(const Eigen::Matrix<double, dim, 1> &,                     \
                                            const Eigen::Matrix<double, dim, 1> &);                    \
  template RigidObstacle<dim> make_spikes<dim>(const Eigen::Matrix<double, dim, 1> &, double,          \
                                               unsigned int, double);                                  \
  template RigidObstacle<dim> read_obj<dim>(const std::string &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
