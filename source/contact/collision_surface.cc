#include <ritr/contact/collision_surface.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ritr::contact
{
  template <int dim>
  void CollisionSurface<dim>::check() const
  {
    const auto fail = [](const std::string &what) {
      throw std::invalid_argument("CollisionSurface: " + what);
    };
    const auto valid = [this](const int v) { return v >= 0 && v < n_vertices; };
    if (n_vertices < 0)
      fail("negative vertex count");
    if (!is_obstacle.empty() && static_cast<int>(is_obstacle.size()) != n_vertices)
      fail("is_obstacle size differs from the vertex count");
    if (!body_id.empty() && static_cast<int>(body_id.size()) != n_vertices)
      fail("body_id size differs from the vertex count");
    if (dim == 1)
      return;
    for (const auto &e : edges)
      if (!valid(e[0]) || !valid(e[1]) || e[0] == e[1])
        fail("invalid edge");
    if (dim == 2 && !faces.empty())
      fail("faces given in 2D");
    for (const auto &f : faces)
      if (!valid(f[0]) || !valid(f[1]) || !valid(f[2]) || f[0] == f[1] || f[1] == f[2] ||
          f[0] == f[2])
        fail("invalid face");
  }

  std::vector<std::array<int, 2>> edges_of_faces(const std::vector<std::array<int, 3>> &faces)
  {
    std::vector<std::array<int, 2>> edges;
    edges.reserve(3 * faces.size());
    for (const auto &f : faces)
      for (int i = 0; i < 3; ++i)
        {
          const int a = f[i], b = f[(i + 1) % 3];
          edges.push_back({{std::min(a, b), std::max(a, b)}});
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
  }

  template struct CollisionSurface<1>;
  template struct CollisionSurface<2>;
  template struct CollisionSurface<3>;
} // namespace ritr::contact
