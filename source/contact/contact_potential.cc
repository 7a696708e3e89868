#include <ritr/contact/contact_potential.h>
#include <ritr/contact/intersection.h>

#include <ritr/common/second_order_dual.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>
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

    // Measure of a body boundary facet and its derivatives w.r.t. the facet's reference node
    // positions (variables: node a component k at a * dim + k).
    template <int dim>
    SecondOrderDual<dim * dim> facet_measure(const std::array<unsigned int, dim> &facet, const Eigen::VectorXd &u)
    {
      using Dual = SecondOrderDual<dim * dim>;
      std::array<std::array<Dual, dim>, dim> p;
      for (int a = 0; a < dim; ++a)
        for (int k = 0; k < dim; ++k)
          p[a][k] = Dual::variable(a * dim + k, u[facet[a] * dim + k]);
      if constexpr (dim == 1)
        return Dual(1.0);
      else if constexpr (dim == 2)
        return sqrt(square(p[1][0] - p[0][0]) + square(p[1][1] - p[0][1]));
      else
        {
          std::array<Dual, 3> e1, e2;
          for (int k = 0; k < 3; ++k)
            {
              e1[k] = p[1][k] - p[0][k];
              e2[k] = p[2][k] - p[0][k];
            }
          const Dual n0 = e1[1] * e2[2] - e1[2] * e2[1], n1 = e1[2] * e2[0] - e1[0] * e2[2],
                     n2 = e1[0] * e2[1] - e1[1] * e2[0];
          return 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
        }
    }
  } // namespace

  template <int dim>
  ContactPotential<dim>::ContactPotential(const SimplexMesh<dim> &mesh,
                                          const std::vector<contact::RigidObstacle<dim>> &obstacles,
                                          const ContactSettings &settings)
    : settings_(settings)
    , mesh_(mesh)
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
  void ContactPotential<dim>::set_reference(const Eigen::VectorXd &u)
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
    // Lagged friction forces scale with their (now changed) weights.
    for (std::size_t j = 0; j < friction_.size(); ++j)
      {
        double w = 0;
        for (const auto &[facet, share] : friction_sources_[j])
          w += share * facet_measure<dim>(mesh_.boundary_facets[facet], u).value;
        if (!friction_sources_[j].empty())
          friction_[j].normal_force = friction_unit_force_[j] * w;
      }
  }

  template <int dim>
  Eigen::MatrixXd ContactPotential<dim>::collision_positions(const Eigen::VectorXd &z) const
  {
    Eigen::MatrixXd V(surface_.n_vertices, dim);
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      V.row(cv) = z.template segment<dim>(state_vertex_[cv] * dim).transpose();
    return V;
  }

  template <int dim>
  std::vector<contact::Constraint> ContactPotential<dim>::active_constraints(const Eigen::MatrixXd &V,
                                                                           const CollisionCandidates &candidates) const
  {
    auto constraints = contact::build_constraints<dim>(surface_, candidates, V, rest_positions_, settings_.dhat);
    if (!settings_.self_contact)
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
  void ContactPotential<dim>::scatter_gradient(const Eigen::VectorXd &gc, const double scale,
                                               Eigen::VectorXd &g) const
  {
    for (int cv = 0; cv < surface_.n_vertices; ++cv)
      g.template segment<dim>(state_vertex_[cv] * dim) += scale * gc.template segment<dim>(cv * dim);
  }

  template <int dim>
  void ContactPotential<dim>::scatter_hessian(const std::vector<Eigen::Triplet<double>> &hc, const double scale,
                                              std::vector<Eigen::Triplet<double>> &h) const
  {
    h.reserve(h.size() + hc.size());
    for (const auto &t : hc)
      h.emplace_back(state_vertex_[t.row() / dim] * dim + t.row() % dim,
                     state_vertex_[t.col() / dim] * dim + t.col() % dim, scale * t.value());
  }

  template <int dim>
  void ContactPotential<dim>::update_friction(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates,
                                              const Eigen::VectorXd &z_start)
  {
    friction_.clear();
    friction_start_ = collision_positions(z_start);
    if (settings_.friction_coefficient <= 0 || dim == 1)
      return;
    const Eigen::MatrixXd V = collision_positions(z_lagged);
    friction_sources_.clear();
    friction_unit_force_.clear();
    // One constraint at a time, so that each friction term keeps its weight's sources.
    for (const auto &c : active_constraints(V, candidates))
      for (const auto &f :
           contact::build_friction_constraints<dim>({c}, V, settings_.dhat, kappa_, weights_, settings_.friction_coefficient))
        {
          friction_.push_back(f);
          friction_sources_.push_back(weight_sources(c));
          friction_unit_force_.push_back(f.normal_force / weights_.weight(c));
        }
  }

  template <int dim>
  const typename ContactPotential<dim>::WeightSources &
  ContactPotential<dim>::weight_sources(const contact::Constraint &c) const
  {
    return c.weight_owner == contact::WeightOwner::vertex ? vertex_sources_[c.weight_index] : edge_sources_[c.weight_index];
  }

  template <int dim>
  void ContactPotential<dim>::reference_derivatives(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                                    ReferenceDerivatives &out) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    out.gu                  = Eigen::VectorXd::Zero(mesh_.n_nodes() * dim);
    out.huu.clear();
    out.hxu.clear();

    // Every contact term is w(u) e(x) with w a sum of shares of facet measures, so its
    // u-derivatives are e dm/du and its mixed derivatives de/dx dm/du^T.
    const auto add_term = [&](const WeightSources &sources, const double energy, const auto &stencil,
                              const auto &stencil_gradient) {
      for (const auto &[facet, share] : sources)
        {
          const auto  m     = facet_measure<dim>(mesh_.boundary_facets[facet], reference_);
          const auto &nodes = mesh_.boundary_facets[facet];
          for (int i = 0; i < dim * dim; ++i)
            {
              const unsigned int ui = nodes[i / dim] * dim + i % dim;
              out.gu[ui] += share * energy * m.grad[i];
              for (int j = 0; j < dim * dim; ++j)
                out.huu.emplace_back(ui, nodes[j / dim] * dim + j % dim, share * energy * m.hess(i, j));
              for (std::size_t s = 0; s < stencil.size(); ++s)
                for (int k = 0; k < dim; ++k)
                  out.hxu.emplace_back(state_vertex_[stencil[s]] * dim + k, ui,
                                       share * stencil_gradient[s * dim + k] * m.grad[i]);
            }
        }
    };

    const auto constraints = active_constraints(V, candidates);
    const auto terms       = contact::unweighted_barrier_terms<dim>(constraints, V, settings_.dhat);
    for (std::size_t k = 0; k < constraints.size(); ++k)
      {
        const std::vector<int> stencil(constraints[k].vertices.begin(),
                                       constraints[k].vertices.begin() + constraints[k].n_vertices);
        const Eigen::VectorXd  gradient = kappa_ * terms[k].gradient;
        add_term(weight_sources(constraints[k]), kappa_ * terms[k].value, stencil, gradient);
      }
    // Friction: D = sum_j w_j(u) Dhat_j(x) with the lagged normal force per unit weight.
    for (std::size_t j = 0; j < friction_.size(); ++j)
      {
        auto unit         = friction_[j];
        unit.normal_force = friction_unit_force_[j];
        const std::vector<contact::FrictionConstraint<dim>> one{unit};
        const double energy = contact::friction_energy<dim>(one, V, friction_start_, settings_.epsilon_v_times_h);
        const Eigen::VectorXd full =
          contact::friction_gradient<dim>(one, V, friction_start_, settings_.epsilon_v_times_h);
        std::vector<int> stencil(unit.vertices.begin(), unit.vertices.begin() + unit.n_vertices);
        Eigen::VectorXd  gradient(stencil.size() * dim);
        for (std::size_t s = 0; s < stencil.size(); ++s)
          gradient.segment<dim>(s * dim) = full.segment<dim>(stencil[s] * dim);
        add_term(friction_sources_[j], energy, stencil, gradient);
      }
  }

  template <int dim>
  double ContactPotential<dim>::value(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    double e = kappa_ * contact::barrier_energy<dim>(active_constraints(V, candidates), V, settings_.dhat, weights_);
    if (!friction_.empty())
      e += contact::friction_energy<dim>(friction_, V, friction_start_, settings_.epsilon_v_times_h);
    return e;
  }

  template <int dim>
  void ContactPotential<dim>::add_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                           Eigen::VectorXd &g) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    scatter_gradient(contact::barrier_gradient<dim>(active_constraints(V, candidates), V, settings_.dhat, weights_), kappa_, g);
    if (!friction_.empty())
      scatter_gradient(contact::friction_gradient<dim>(friction_, V, friction_start_, settings_.epsilon_v_times_h), 1.0, g);
  }

  template <int dim>
  void ContactPotential<dim>::add_hessian(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                                          std::vector<Eigen::Triplet<double>> &h,
                                          const bool project) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    scatter_hessian(contact::barrier_hessian<dim>(active_constraints(V, candidates), V, settings_.dhat, weights_, project), kappa_, h);
    if (!friction_.empty())
      scatter_hessian(contact::friction_hessian<dim>(friction_, V, friction_start_, settings_.epsilon_v_times_h, project), 1.0, h);
  }

  template <int dim>
  Eigen::VectorXd ContactPotential<dim>::barrier_gradient(const Eigen::VectorXd &z,
                                                          const CollisionCandidates &candidates) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    Eigen::VectorXd       g = Eigen::VectorXd::Zero(z.size());
    scatter_gradient(contact::barrier_gradient<dim>(active_constraints(V, candidates), V, settings_.dhat, weights_), 1.0, g);
    return g;
  }

  template <int dim>
  CollisionCandidates ContactPotential<dim>::candidates_at(const Eigen::VectorXd &z) const
  {
    return contact::find_candidates<dim>(surface_, collision_positions(z), settings_.dhat);
  }

  template <int dim>
  CollisionCandidates ContactPotential<dim>::candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    return contact::find_candidates<dim>(surface_, collision_positions(z), collision_positions(z + dz), settings_.dhat);
  }

  template <int dim>
  double ContactPotential<dim>::max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const
  {
    const Eigen::MatrixXd V0 = collision_positions(z), V1 = collision_positions(z + dz);
    // Inflating by dhat keeps the separation guarantee (d >= 0.1 d0) for every pair that can
    // come within the barrier's range, not only for pairs whose swept boxes touch: a pair
    // ending exactly in contact could otherwise slip through with a round-off-sized gap.
    return contact::max_step<dim>(surface_, V0, V1, 0.1, settings_.dhat);
  }

  template <int dim>
  double ContactPotential<dim>::minimum_distance(const Eigen::VectorXd &z) const
  {
    return contact::minimum_distance<dim>(surface_, collision_positions(z));
  }

  template <int dim>
  bool ContactPotential<dim>::has_intersections(const Eigen::VectorXd &z) const
  {
    return contact::has_intersections<dim>(surface_, collision_positions(z));
  }

  template <int dim>
  double ContactPotential<dim>::active_minimum_distance(const Eigen::VectorXd &z,
                                                      const CollisionCandidates &candidates) const
  {
    const Eigen::MatrixXd V = collision_positions(z);
    return contact::minimum_distance<dim>(active_constraints(V, candidates), V);
  }

  template <int dim>
  double ContactPotential<dim>::bbox_diagonal(const Eigen::VectorXd &z) const
  {
    return contact::bbox_diagonal(collision_positions(z));
  }

  template class ContactPotential<1>;
  template class ContactPotential<2>;
  template class ContactPotential<3>;
} // namespace ritr
