#pragma once
// The collision geometry of a simulation, in the spirit of IPC Toolkit's CollisionMesh: the
// collision surface made of the bodies' boundary facets and the rigid obstacles, the map from
// its vertices to entries of the state z = [body node positions, obstacle vertices], and the
// weight of every contact constraint, the reference boundary measure of its point (or edge)
// -- a function of the body's reference positions u, so that contact terms depend on u too.
// Candidates, distances and CCD are geometry queries on a state; the barrier and friction
// terms (terms/) are built on top.
#include <ritr/contact/barrier.h>
#include <ritr/contact/ccd.h>
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/constraints.h>
#include <ritr/contact/rigid_obstacle.h>
#include <ritr/common/triplets.h>
#include <ritr/mesh/simplex_mesh.h>

#include <array>
#include <optional>
#include <utility>
#include <vector>

namespace ritr
{
  // The broad-phase pairs one evaluation looks at. Callers build them (at a state, or along
  // a step for the line search) and pass them in, so that what an evaluation sees never
  // depends on which evaluation ran before it.
  using CollisionCandidates = std::vector<contact::Candidate>;

  template <int dim>
  class CollisionMesh
  {
  public:
    // `self_contact`: primitives of the bodies also repel each other, not only obstacles.
    CollisionMesh(const SimplexMesh<dim> &mesh, const std::vector<contact::RigidObstacle<dim>> &obstacles,
                  double dhat, bool self_contact);

    // Reference positions u of the body nodes: rest positions of the body's collision
    // vertices and the constraint weights (obstacle vertices weigh by their own measure).
    void set_reference(const Eigen::VectorXd &u);
    const Eigen::VectorXd            &reference() const { return reference_; }
    const contact::ConstraintWeights &weights() const { return weights_; }
    double                            dhat() const { return dhat_; }
    // Mean weight of the bodies' collision vertices: the scale of one constraint's weight.
    double mean_body_vertex_weight() const;

    // Collision vertex positions (rows) of the state z.
    Eigen::MatrixXd vertices(const Eigen::VectorXd &z) const;
    // The candidates' pairs within dhat at V (without body-body pairs unless self contact).
    std::vector<contact::Constraint> active_constraints(const Eigen::MatrixXd &V, const CollisionCandidates &candidates) const;

    // Pairs within dhat at z, and pairs whose boxes swept from z to z + dz (inflated by dhat)
    // overlap: the latter cover every state of the segment.
    CollisionCandidates candidates_at(const Eigen::VectorXd &z) const;
    CollisionCandidates candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;

    // Largest fraction of dz that continuous collision detection certifies; `along` are
    // candidates_along(z, dz) when the caller has them already.
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz, const CollisionCandidates &along) const;
    double minimum_distance(const Eigen::VectorXd &z) const;  // over all primitive pairs
    bool   has_intersections(const Eigen::VectorXd &z) const;  // crossing primitives
    // For naming what overlaps at z: a state vertex of each of two crossing primitives, or of
    // two primitives closer than `distance`; nothing when there are none.
    std::optional<std::array<int, 2>> crossing_vertices(const Eigen::VectorXd &z) const;
    std::optional<std::array<int, 2>> vertices_closer_than(const Eigen::VectorXd &z, double distance) const;
    // Over the candidates' pairs within dhat.
    double active_minimum_distance(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;
    double bbox_diagonal(const Eigen::VectorXd &z) const;

    // Collision-vertex gradients and Hessians, times `scale`, added in state numbering.
    void scatter_gradient(const Eigen::VectorXd &gc, double scale, Eigen::VectorXd &g) const;
    void scatter_hessian(const Triplets &hc, double scale, Triplets &h) const;
    int  state_vertex(int collision_vertex) const { return state_vertex_[collision_vertex]; }

    // The body boundary facets a constraint's weight is made of, each with its share (1/dim
    // of a facet per vertex, 1/3 of a face per edge); empty for obstacle weights.
    using WeightSources = std::vector<std::pair<unsigned int, double>>;
    const WeightSources &weight_sources(const contact::Constraint &c) const;
    // sum_sources share * |facet| at the current reference.
    double weight_of(const WeightSources &sources) const;

    // dw/du of the weight made of `sources`, as (reference entry, derivative) pairs (an entry
    // may repeat: facets share nodes).
    std::vector<std::pair<unsigned int, double>> weight_gradient(const WeightSources &sources) const;

    // The u-derivatives of a contact term w(u) e(x), w made of `sources`: e dw/du into gu and
    // e d2w/du2 into huu (reference numbering), de/dx dw/du^T into hxu (rows: state, columns:
    // reference). `stencil` lists the term's collision vertices, `stencil_gradient` is de/dx
    // on them (dim entries per vertex).
    void add_weight_derivatives(const WeightSources &sources, double energy, const std::vector<int> &stencil,
                                const Eigen::VectorXd &stencil_gradient, Eigen::VectorXd &gu, Triplets &huu,
                                Triplets &hxu) const;

    unsigned int                          n_collision_vertices() const { return surface_.n_vertices; }
    unsigned int                          n_state_vertices() const { return n_state_vertices_; }
    const contact::CollisionSurface<dim> &surface() const { return surface_; }
    const SimplexMesh<dim>               &mesh() const { return mesh_; }

  private:
    const SimplexMesh<dim>        &mesh_;
    double                         dhat_;
    bool                           self_contact_;
    contact::CollisionSurface<dim> surface_;
    std::vector<int>               state_vertex_;  // collision vertex -> state vertex
    unsigned int                   n_state_vertices_ = 0;
    Eigen::MatrixXd                rest_positions_;
    Eigen::VectorXd                reference_;  // body reference positions u
    contact::ConstraintWeights     weights_;
    std::vector<WeightSources>     vertex_sources_, edge_sources_;
  };
} // namespace ritr
