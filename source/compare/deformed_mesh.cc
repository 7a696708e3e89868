#include <ritr/compare/deformed_mesh.h>
#include <ritr/compare/vtk_reader.h>

#include <cmath>

namespace ritr::compare
{
  namespace
  {
    Point minus(const Point &a, const Point &b)
    {
      return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    }

    Point cross(const Point &a, const Point &b)
    {
      return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }

    double norm(const Point &a)
    {
      return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    }

    // Length, area or volume of a simplex given by its vertices.
    double measure(const std::vector<Point> &v)
    {
      switch (v.size())
        {
          case 2: return norm(minus(v[1], v[0]));
          case 3: return 0.5 * norm(cross(minus(v[1], v[0]), minus(v[2], v[0])));
          case 4:
            {
              const Point n = cross(minus(v[1], v[0]), minus(v[2], v[0]));
              const Point e = minus(v[3], v[0]);
              return std::abs(n[0] * e[0] + n[1] * e[1] + n[2] * e[2]) / 6.0;
            }
          default: return 0.0;
        }
    }
  } // namespace

  double distance(const Point &a, const Point &b)
  {
    return norm(minus(a, b));
  }

  Point centroid(const DeformedMesh &mesh)
  {
    Point  weighted_sum{0.0, 0.0, 0.0};
    double total_measure = 0.0;
    for (const auto &cell : mesh.cells)
      {
        std::vector<Point> vertices;
        for (const unsigned int i : cell)
          vertices.push_back(mesh.points[i]);
        const double m = measure(vertices);
        for (const Point &p : vertices)
          for (int k = 0; k < 3; ++k)
            weighted_sum[k] += m * p[k] / vertices.size();
        total_measure += m;
      }
    for (double &c : weighted_sum)
      c /= total_measure;
    return weighted_sum;
  }
  DeformedMesh read_deformed_mesh(const std::filesystem::path &vtu_file)
  {
    VtuGrid grid = read_vtu(vtu_file);
    return {grid.dim, std::move(grid.points), std::move(grid.cells)};
  }
} // namespace ritr::compare
