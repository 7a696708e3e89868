#include <ritr/contact/enclosure.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace ritr::contact
{
  namespace
  {
    // Barycentric coordinates closer than this to 0 or 1 mean that the ray passes (nearly)
    // through a vertex or an edge, where counting crossings is ambiguous.
    constexpr double ambiguous = 1e-9;

    // The number of facets the ray from p along d crosses, or nothing when it passes too close
    // to a facet's vertex or edge, or runs along a facet, to tell.
    std::optional<int> crossings(const Eigen::MatrixXd &V, const std::vector<std::array<int, 2>> &segments,
                                 const Eigen::Vector2d &p, const Eigen::Vector2d &d)
    {
      int count = 0;
      for (const auto &s : segments)
        {
          const Eigen::Vector2d a = V.row(s[0]).transpose(), e = V.row(s[1]).transpose() - a;
          // p + r d = a + t e, solved by Cramer's rule.
          const double det = e[0] * d[1] - e[1] * d[0];
          if (std::abs(det) <= ambiguous * e.norm())
            {
              if (std::abs((a - p)[0] * d[1] - (a - p)[1] * d[0]) <= ambiguous * e.norm())
                return std::nullopt;  // the ray runs along the segment's line
              continue;               // parallel: no crossing
            }
          const Eigen::Vector2d w = a - p;
          const double          t = (d[0] * w[1] - d[1] * w[0]) / det;
          const double          r = (e[0] * w[1] - e[1] * w[0]) / det;
          if (r <= 0 || t < -ambiguous || t > 1 + ambiguous)
            continue;
          if (t < ambiguous || t > 1 - ambiguous)
            return std::nullopt;
          ++count;
        }
      return count;
    }

    std::optional<int> crossings(const Eigen::MatrixXd &V, const std::vector<std::array<int, 3>> &triangles,
                                 const Eigen::Vector3d &p, const Eigen::Vector3d &d)
    {
      int count = 0;
      for (const auto &f : triangles)
        {
          // Moller-Trumbore: p + r d = a + u e1 + v e2.
          const Eigen::Vector3d a = V.row(f[0]).transpose();
          const Eigen::Vector3d e1 = V.row(f[1]).transpose() - a, e2 = V.row(f[2]).transpose() - a;
          const Eigen::Vector3d h   = d.cross(e2);
          const double          det = e1.dot(h);
          if (std::abs(det) <= ambiguous * e1.norm() * e2.norm())
            {
              if (std::abs((p - a).dot(e1.cross(e2).normalized())) <= ambiguous * e1.norm())
                return std::nullopt;  // the ray runs in the triangle's plane
              continue;
            }
          const Eigen::Vector3d s = p - a, q = s.cross(e1);
          const double          u = s.dot(h) / det, v = d.dot(q) / det, r = e2.dot(q) / det;
          if (r <= 0 || u < -ambiguous || v < -ambiguous || u + v > 1 + ambiguous)
            continue;
          if (u < ambiguous || v < ambiguous || u + v > 1 - ambiguous)
            return std::nullopt;
          ++count;
        }
      return count;
    }

    // Directions that no mesh built on a grid or a circle is likely to line up with: the
    // golden angle turns each one away from the last.
    template <int dim>
    Eigen::Matrix<double, dim, 1> ray_direction(const int attempt)
    {
      const double angle = 0.3 + attempt * 2.399963229728653;
      if constexpr (dim == 2)
        return Eigen::Vector2d(std::cos(angle), std::sin(angle));
      else
        {
          const double height = std::fmod(0.37 + attempt * 0.6180339887498949, 1.0) * 1.8 - 0.9;
          const double radius = std::sqrt(1 - height * height);
          return Eigen::Vector3d(radius * std::cos(angle), height, radius * std::sin(angle));
        }
    }
  } // namespace

  template <int dim>
  bool is_closed(const std::vector<std::array<int, dim>> &facets)
  {
    // 2D: each vertex ends an even number of segments; 3D: each edge borders an even number
    // of triangles.
    std::map<std::array<int, dim - 1>, int> count;
    for (const auto &f : facets)
      for (int k = 0; k < dim; ++k)
        {
          std::array<int, dim - 1> boundary;
          for (int j = 0; j < dim - 1; ++j)
            boundary[j] = f[(k + j) % dim];
          std::sort(boundary.begin(), boundary.end());
          ++count[boundary];
        }
    return !facets.empty() &&
           std::all_of(count.begin(), count.end(), [](const auto &entry) { return entry.second % 2 == 0; });
  }

  template <int dim>
  bool encloses(const Eigen::MatrixXd &V, const std::vector<std::array<int, dim>> &facets,
                const Eigen::Matrix<double, dim, 1> &point)
  {
    std::optional<int> count;
    for (int attempt = 0; attempt < 64 && !count; ++attempt)
      count = crossings(V, facets, point, ray_direction<dim>(attempt));
    return count && *count % 2 == 1;
  }

  template bool is_closed<2>(const std::vector<std::array<int, 2>> &);
  template bool is_closed<3>(const std::vector<std::array<int, 3>> &);
  template bool encloses<2>(const Eigen::MatrixXd &, const std::vector<std::array<int, 2>> &, const Eigen::Vector2d &);
  template bool encloses<3>(const Eigen::MatrixXd &, const std::vector<std::array<int, 3>> &, const Eigen::Vector3d &);
} // namespace ritr::contact
