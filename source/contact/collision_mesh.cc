#include <ritr/common/simplex_measure.h>
#include <ritr/contact/collision_mesh.h>
#include <ritr/contact/intersection.h>

#include <algorithm>
#include <map>

namespace ritr
{
  namespace
  {
    // Length / area of a boundary primitive given its vertex positions (1D: a point weighs 1).
    template <int dim>
    double primitive_measure(const std::vector<Eigen::Matrix<double, dim, 1>> &p)
    {
      if constexpr (dim == 1)
        return 1.0;
      else if constexpr (dim == 2)
        return (p[1] - p[0]).norm();
      else
        return 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    }
  } // namespace

  template <int dim>
  CollisionMesh<dim>::CollisionMesh(const SimplexMesh<dim> &mesh, const std::vector<contact::RigidObstacle<dim>> &obstacles,
                                    const double dhat, const bool self_contact)
    : mesh_(mesh)
    , dhat_(dhat)
    , self_contact_(self_contact)
  {
    // Collision vertices: the body's boundary nodes, then every obstacle vertex.
    std::vector<int> node_to_collision(mesh.n_nodes(), -1);
    for (const auto &facet : mesh.boundary_facets)
      for (const unsigned int n : facet)
        if (node_to_collision[n] < 0)
          {
            node_to_collision[n] = state_vertex_.size();
            state_vertex_.push_back(n);
            surface_.is_obstacle.push_back(false);
            surface_.body_id.push_back(mesh.node_body[n]);
          }
    std::vector<int> obstacle_offset;
    unsigned int     n_obstacle_vertices = 0;
    for (const auto &o : obstacles)
      {
        obstacle_offset.push_back(state_vertex_.size());
        for (std::size_t v = 0; v < o.rest_vertices.size(); ++v)
          {
            state_vertex_.push_back(mesh.n_nodes() + n_obstacle_vertices + v);
            surface_.is_obstacle.push_back(true);
            surface_.body_id.push_back(-1);
          }
        n_obstacle_vertices += o.rest_vertices.size();
      }
    n_state_vertices_   = mesh.n_nodes() + n_obstacle_vertices;
    surface_.n_vertices = state_vertex_.size();

    if constexpr (dim == 2)
      {
        for (const auto &f : mesh.boundary_facets)
          surface_.edges.push_back({node_to_collision[f[0]], node_to_collision[f[1]]});
        for (std::size_t o = 0; o < obstacles.size(); ++o)
          for (const auto &e : obstacles[o].edges)
            surface_.edges.push_back({obstacle_offset[o] + e[0], obstacle_offset[o] + e[1]});
      }
    else if constexpr (dim == 3)
      {
        for (const auto &f : mesh.boundary_facets)
          surface_.faces.push_back({node_to_collision[f[0]], node_to_collision[f[1]], node_to_collision[f[2]]});
        for (std::size_t o = 0; o < obstacles.size(); ++o)
          for (const auto &f : obstacles[o].faces)
            surface_.faces.push_back({obstacle_offset[o] + f[0], obstacle_offset[o] + f[1], obstacle_offset[o] + f[2]});
        surface_.edges = contact::edges_of_faces(surface_.faces);
      }
    surface_.check();

    // Which body facets make up each weight (obstacle weights do not depend on u).
    vertex_sources_.resize(surface_.n_vertices);
    edge_sources_.resize(surface_.edges.size());
    if constexpr (dim > 1)
      {
        std::map<std::array<int, 2>, int> edge_index;
        for (std::size_t i = 0; i < surface_.edges.size(); ++i)
          edge_index[{std::min(surface_.edges[i][0], surface_.edges[i][1]),
                      std::max(surface_.edges[i][0], surface_.edges[i][1])}] = i;
        for (unsigned int f = 0; f < mesh.boundary_facets.size(); ++f)
          for (int a = 0; a < dim; ++a)
            {
              const int cv = node_to_collision[mesh.boundary_facets[f][a]];
              vertex_sources_[cv].emplace_back(f, 1.0 / dim);
              if constexpr (dim == 3)
                {
                  const int next = node_to_collision[mesh.boundary_facets[f][(a + 1) % 3]];
                  edge_sources_[edge_index.at({std::min(cv, next), std::max(cv, next)})].emplace_back(f, 1.0 / 3);
                }
            }
      }

    rest_positions_.resize(surface_.n_vertices, dim);
    for (std::size_t o = 0; o < obstacles.size(); ++o)
      for (std::size_t v = 0; v < obstacles[o].rest_vertices.size(); ++v)
        rest_positions_.row(obstacle_offset[o] + v) = obstacles[o].rest_vertices[v].transpose();
    set_reference(mesh.reference);
  }

  template <int dim>
  void CollisionMesh<dim>::set_reference(const Eigen::VectorXd &u)
  {
    reference_ = u;
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      if (!surface_.is_obstacle[cv])
        rest_positions_.row(cv) = u.template segment<dim>(state_vertex_[cv] * dim).transpose();

    // Each primitive's measure is shared equally by its vertices (and in 3D by its edges).
    weights_.vertex_weights.assign(surface_.n_vertices, 0.0);
    weights_.edge_weights.assign(surface_.edges.size(), 0.0);
    const auto position = [&](int cv) { return Eigen::Matrix<double, dim, 1>(rest_positions_.row(cv).transpose()); };
    if constexpr (dim == 1)
      std::fill(weights_.vertex_weights.begin(), weights_.vertex_weights.end(), 1.0);
    else if constexpr (dim == 2)
      for (const auto &e : surface_.edges)
        {
          const double m = primitive_measure<dim>({position(e[0]), position(e[1])});
          for (const int v : e)
            weights_.vertex_weights[v] += m / 2;
        }
    else
      {
        std::map<std::array<int, 2>, int> edge_index;
        for (std::size_t i = 0; i < surface_.edges.size(); ++i)
          edge_index[surface_.edges[i]] = i;
        for (const auto &f : surface_.faces)
          {
            const double m = primitive_measure<dim>({position(f[0]), position(f[1]), position(f[2])});
            for (int a = 0; a < 3; ++a)
              {
                weights_.vertex_weights[f[a]] += m / 3;
                const int b = f[(a + 1) % 3];
                weights_.edge_weights[edge_index.at({std::min(f[a], b), std::max(f[a], b)})] += m / 3;
              }
          }
      }
  }

  template <int dim>
  double CollisionMesh<dim>::mean_body_vertex_weight() const
  {
    double       sum = 0.0;
    unsigned int n   = 0;
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      if (!surface_.vertex_is_obstacle(cv))
        {
          sum += weights_.vertex_weights[cv];
          ++n;
        }
    return n > 0 && sum > 0.0 ? sum / n : 1.0;
  }

  template <int dim>
  Eigen::MatrixXd CollisionMesh<dim>::vertices(const Eigen::VectorXd &z) const
  {
    Eigen::MatrixXd V(surface_.n_vertices, dim);
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      V.row(cv) = z.template segment<dim>(state_vertex_[cv] * dim).transpose();
    return V;
  }

  template <int dim>
  std::vector<contact::Constraint> CollisionMesh<dim>::active_constraints(const Eigen::MatrixXd     &V,
                                                                          const CollisionCandidates &candidates) const
  {
    auto constraints = contact::build_constraints<dim>(surface_, candidates, V, rest_positions_, dhat_);
    if (!self_contact_)
      constraints.erase(std::remove_if(constraints.begin(), constraints.end(),
                                       [&](const contact::Constraint &c) {
                                         for (int i = 0; i < c.n_vertices; ++i)
                                           if (surface_.is_obstacle[c.vertices[i]])
                                             return false;
                                         return true;
                                       }),
                        constraints.end());
    return constraints;
  }

  template <int dim>
  void CollisionMesh<dim>::scatter_gradient(const Eigen::VectorXd &gc, const double scale, Eigen::VectorXd &g) const
  {
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      g.template segment<dim>(state_vertex_[cv] * dim) += scale * gc.template segment<dim>(cv * dim);
  }

  template <int dim>
  void CollisionMesh<dim>::scatter_hessian(const Triplets &hc, const double scale, Triplets &h) const
  {
    h.reserve(h.size() + hc.size());
    for (const auto &t : hc)
      h.emplace_back(state_vertex_[t.row() / dim] * dim + t.row() % dim,
                     state_vertex_[t.col() / dim] * dim + t.col() % dim, scale * t.value());
  }

  template <int dim>
  const typename CollisionMesh<dim>::WeightSources &CollisionMesh<dim>::weight_sources(const contact::Constraint &c) const
  {
    return c.weight_owner == contact::WeightOwner::vertex ? vertex_sources_[c.weight_index] : edge_sources_[c.weight_index];
  }

  template <int dim>
  double CollisionMesh<dim>::weight_of(const WeightSources &sources) const
  {
    double w = 0;
    for (const auto &[facet, share] : sources)
      w += share * facet_measure_derivatives<dim>(reference_, mesh_.boundary_facets[facet]).value;
    return w;
  }

  template <int dim>
  std::vector<std::pair<unsigned int, double>> CollisionMesh<dim>::weight_gradient(const WeightSources &sources) const
  {
    std::vector<std::pair<unsigned int, double>> gradient;
    for (const auto &[facet, share] : sources)
      {
        const auto  m     = facet_measure_derivatives<dim>(reference_, mesh_.boundary_facets[facet]);
        const auto &nodes = mesh_.boundary_facets[facet];
        for (int i = 0; i < dim * dim; ++i)
          gradient.emplace_back(nodes[i / dim] * dim + i % dim, share * m.grad[i]);
      }
    return gradient;
  }

  template <int dim>
  void CollisionMesh<dim>::add_weight_derivatives(const WeightSources &sources, const double energy,
                                                  const std::vector<int> &stencil, const Eigen::VectorXd &stencil_gradient,
                                                  Eigen::VectorXd &gu, Triplets &huu, Triplets &hxu) const
  {
    // The term is w(u) e(x) with w a sum of shares of facet measures: its u-derivatives are
    // e dm/du and its mixed derivatives de/dx dm/du^T.
    for (const auto &[facet, share] : sources)
      {
        const auto  m     = facet_measure_derivatives<dim>(reference_, mesh_.boundary_facets[facet]);
        const auto &nodes = mesh_.boundary_facets[facet];
        for (int i = 0; i < dim * dim; ++i)
          {
            const unsigned int ui = nodes[i / dim] * dim + i % dim;
            gu[ui] += share * energy * m.grad[i];
            for (int j = 0; j < dim * dim; ++j)
              huu.emplace_back(ui, nodes[j / dim] * dim + j % dim, share * energy * m.hess(i, j));
            for (std::size_t s = 0; s < stencil.size(); ++s)
              for (int k = 0; k < dim; ++k)
                hxu.emplace_back(state_vertex_[stencil[s]] * dim + k, ui, share * stencil_gradient[s * dim + k] * m.grad[i]);
          }
      }
  }

  template <int dim>
  CollisionCandidates CollisionMesh<dim>::candidates_at(const Eigen::VectorXd &z) const
  {
    return contact::find_candidates<dim>(surface_, vertices(z), dhat_);
  }

  template <int dim>
  CollisionCandidates CollisionMesh<dim>::candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    return contact::find_candidates<dim>(surface_, vertices(z), vertices(z + dz), dhat_);
  }

  template <int dim>
  double CollisionMesh<dim>::max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    return max_step(z, dz, candidates_along(z, dz));
  }

  template <int dim>
  double CollisionMesh<dim>::max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz,
                                      const CollisionCandidates &along) const
  {
    // The candidates along the step are inflated by dhat, which keeps the separation guarantee
    // (d >= 0.1 d0) for every pair that can come within the barrier's range, not only for pairs
    // whose swept boxes touch: a pair ending exactly in contact could otherwise slip through
    // with a round-off-sized gap.
    return contact::max_step<dim>(surface_, vertices(z), vertices(z + dz), along, 0.1);
  }

  template <int dim>
  double CollisionMesh<dim>::minimum_distance(const Eigen::VectorXd &z) const
  {
    return contact::minimum_distance<dim>(surface_, vertices(z));
  }

  template <int dim>
  bool CollisionMesh<dim>::has_intersections(const Eigen::VectorXd &z) const
  {
    return contact::has_intersections<dim>(surface_, vertices(z));
  }

  template <int dim>
  std::optional<std::array<int, 2>> CollisionMesh<dim>::crossing_vertices(const Eigen::VectorXd &z) const
  {
    const auto pair = contact::find_intersection<dim>(surface_, vertices(z));
    if (!pair)
      return std::nullopt;
    return std::array<int, 2>{state_vertex_[(*pair)[0]], state_vertex_[(*pair)[1]]};
  }

  template <int dim>
  std::optional<std::array<int, 2>> CollisionMesh<dim>::vertices_closer_than(const Eigen::VectorXd &z,
                                                                             const double distance) const
  {
    const auto close = contact::build_constraints<dim>(surface_, vertices(z), rest_positions_, distance);
    if (close.empty())
      return std::nullopt;
    // A constraint's stencil lists the first primitive's vertices, then the second's.
    const auto &c = close.front();
    return std::array<int, 2>{state_vertex_[c.vertices[0]], state_vertex_[c.vertices[c.n_vertices - 1]]};
  }

  template <int dim>
  double CollisionMesh<dim>::active_minimum_distance(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const
  {
    const Eigen::MatrixXd V = vertices(z);
    return contact::minimum_distance<dim>(active_constraints(V, candidates), V);
  }

  template <int dim>
  double CollisionMesh<dim>::bbox_diagonal(const Eigen::VectorXd &z) const
  {
    return contact::bbox_diagonal(vertices(z));
  }

  template class CollisionMesh<1>;
  template class CollisionMesh<2>;
  template class CollisionMesh<3>;
} // namespace ritr
