// The checks of a problem's initial state (make_problem's last step): coordinates a double
// can compute with, elements with a measure, no element inverted by the prescribed start,
// and -- with contact -- bodies and obstacles free of intersections: no boundaries crossing
// or touching, and nothing inside a body or a closed obstacle. Each failure names the body
// or obstacle at fault.
#include <ritr/common/input_error.h>
#include <ritr/common/number_text.h>
#include <ritr/contact/enclosure.h>
#include <ritr/metrics/mesh_metrics.h>
#include <ritr/problem/problem.h>

#include <cmath>
#include <limits>

namespace ritr
{
  namespace
  {
    // Lengths are squared (distances), cubed (volumes) and multiplied further in derivatives:
    // coordinates below this keep every such product within the range of doubles.
    constexpr double largest_coordinate = 1e50;


    // One connected body or one obstacle, as the inside tests see it: its boundary facets in
    // state vertex numbering, whether they bound a region, and a vertex of it.
    template <int dim>
    struct Component
    {
      std::string                       name;
      bool                              obstacle = false;
      std::vector<std::array<int, dim>> facets;
      bool                              closed = false;
      int                               vertex = -1;
    };
  } // namespace

  template <int dim>
  std::string Problem<dim>::name_of_state_vertex(const int vertex) const
  {
    if (vertex < static_cast<int>(mesh.n_nodes()))
      {
        const unsigned int part = mesh.node_part[vertex];
        return scene.bodies[part].section;
      }
    int first = mesh.n_nodes();
    for (std::size_t o = 0; o < obstacles.size(); ++o)
      {
        first += obstacles[o].rest_vertices.size();
        if (vertex < first)
          return scene.obstacles[o].section;
      }
    return "Obstacle";
  }

  template <int dim>
  void Problem<dim>::check_initial_state() const
  {
    check_coordinates();
    check_element_measures();
    if (!(min_deformed_jacobian(mesh, initial_positions, initial_reference) > 0))
      throw InputError(scene.start_from.empty() ?
                         scene.parameter_file + ": Dirichlet: the initial prescribed displacement inverts elements" :
                         scene.where("start from") + ": the frame's state inverts elements of the scene's mesh");
    if (collisions)
      {
        Eigen::VectorXd z(initial_positions.size() + initial_obstacle_positions.size());
        z << initial_positions, initial_obstacle_positions;
        check_separation(z);
        if constexpr (dim > 1)
          check_nothing_inside(z);
      }
  }

  template <int dim>
  void Problem<dim>::check_coordinates() const
  {
    const auto check = [&](const Eigen::VectorXd &positions, const int first_vertex) {
      for (Eigen::Index i = 0; i < positions.size(); ++i)
        if (!(std::abs(positions[i]) <= largest_coordinate))
          throw InputError(scene.where(name_of_state_vertex(first_vertex + i / dim)) + ": has a coordinate of " + number_text(positions[i]) + "; coordinates must stay below " +
                           number_text(largest_coordinate) + " in magnitude (choose other units)");
    };
    check(initial_reference, 0);
    check(initial_positions, 0);
    check(initial_obstacle_positions, mesh.n_nodes());
  }

  template <int dim>
  void Problem<dim>::check_element_measures() const
  {
    double       smallest = std::numeric_limits<double>::max(), largest = 0;
    unsigned int smallest_cell = 0;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const double m = std::abs(simplex_measure<dim, double>(cell_nodes<dim>(initial_reference, mesh.cells[c])));
        if (m < smallest)
          {
            smallest      = m;
            smallest_cell = c;
          }
        largest = std::max(largest, m);
      }
    if (!(smallest > 1e-12 * largest))
      throw InputError(scene.where(name_of_state_vertex(mesh.cells[smallest_cell][0])) +
                       ": the mesh has degenerate (zero-measure) elements");
  }

  template <int dim>
  void Problem<dim>::check_separation(const Eigen::VectorXd &z) const
  {
    const auto refuse = [&](const std::array<int, 2> &pair) {
      const std::string a = name_of_state_vertex(pair[0]), b = name_of_state_vertex(pair[1]);
      throw InputError(scene.parameter_file + ": the initial configuration intersects: " +
                       (a == b ? a + " touches or crosses itself" : a + " and " + b + " overlap or touch"));
    };
    if (const auto crossing = collisions->crossing_vertices(z))
      refuse(*crossing);
    // Distances at round-off level are contact too: the barrier could not push them apart.
    const double round_off = 1e-12 * collisions->bbox_diagonal(z);
    if (!(collisions->minimum_distance(z) > round_off))
      {
        if (const auto close = collisions->vertices_closer_than(z, round_off))
          refuse(*close);
        throw InputError(scene.parameter_file + ": the initial configuration intersects (bodies or obstacles touch)");
      }
  }

  template <int dim>
  void Problem<dim>::check_nothing_inside(const Eigen::VectorXd &z) const
  {
    if constexpr (dim > 1)
      {
        const Eigen::MatrixXd V =
          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, dim, Eigen::RowMajor>>(z.data(), z.size() / dim, dim);
        // The bodies' connected components, then the obstacles.
        std::vector<Component<dim>> components(mesh.n_bodies());
        for (const auto &facet : mesh.boundary_facets)
          {
            auto &body = components[mesh.node_body[facet[0]]];
            body.facets.emplace_back();
            std::copy(facet.begin(), facet.end(), body.facets.back().begin());
          }
        for (auto &body : components)
          body.closed = true;  // the boundary of a mesh
        int first = mesh.n_nodes();
        for (const auto &o : obstacles)
          {
            Component<dim> obstacle;
            obstacle.obstacle = true;
            if constexpr (dim == 2)
              for (const auto &e : o.edges)
                obstacle.facets.push_back({{first + e[0], first + e[1]}});
            else
              for (const auto &f : o.faces)
                obstacle.facets.push_back({{first + f[0], first + f[1], first + f[2]}});
            obstacle.closed = contact::is_closed<dim>(obstacle.facets);
            components.push_back(obstacle);
            first += o.rest_vertices.size();
          }
        for (auto &c : components)
          if (!c.facets.empty())
            {
              c.vertex = c.facets.front()[0];
              c.name   = name_of_state_vertex(c.vertex);
            }

        // Boundaries do not cross (check_separation): a component is wholly inside another
        // or wholly outside it, and one of its vertices tells which.
        for (const auto &inner : components)
          for (const auto &outer : components)
            if (&inner != &outer && outer.closed && inner.vertex >= 0 && !(inner.obstacle && outer.obstacle) &&
                contact::encloses<dim>(V, outer.facets, V.row(inner.vertex).transpose()))
              throw InputError(scene.parameter_file + ": the initial configuration intersects: " +
                               (inner.name == outer.name ? "a part of " + inner.name + " lies inside another part" :
                                                           inner.name + " lies inside " + outer.name));
      }
  }

#define RITR_INSTANTIATE(dim)                                                                                          \
  template std::string Problem<dim>::name_of_state_vertex(int) const;                                                 \
  template void        Problem<dim>::check_initial_state() const;                                                     \
  template void        Problem<dim>::check_coordinates() const;                                                       \
  template void        Problem<dim>::check_element_measures() const;                                                  \
  template void        Problem<dim>::check_separation(const Eigen::VectorXd &) const;                                 \
  template void        Problem<dim>::check_nothing_inside(const Eigen::VectorXd &) const;
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
