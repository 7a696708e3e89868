#pragma once
// Couples the IPC module to the simulation: the collision surface made of the mesh's
// boundary facets and the rigid obstacles, the barrier weights (reference boundary
// measure), and barrier + lagged friction energies over the simulation state vector
// z = [body node positions, obstacle vertex positions].
#include <ritr/contact/barrier.h>
#include <ritr/contact/ccd.h>
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/constraints.h>
#include <ritr/contact/friction.h>
#include <ritr/contact/rigid_obstacle.h>
#include <ritr/mesh/simplex_mesh.h>

#include <Eigen/Sparse>


namespace ritr
{
  struct ContactSettings
  {
    double dhat                 = 1e-3;
    double friction_coefficient = 0.0;
    double epsilon_v_times_h    = 1e-5;
    bool   self_contact         = true;
  };

  // The broad-phase pairs one evaluation looks at. Callers build them (at a state, or along
  // a step for the line search) and pass them in, so that what an evaluation sees never
  // depends on which evaluation ran before it.
  using CollisionCandidates = std::vector<contact::Candidate>;

  template <int dim>
  class ContactPotential
  {
  public:
    ContactPotential(const SimplexMesh<dim> &mesh,
                     const std::vector<contact::RigidObstacle<dim>> &obstacles,
                     const ContactSettings &settings);

    // Reference boundary measures of the body nodes at reference positions u (the barrier
    // weights; obstacle vertices weigh by their own surface measure).
    void set_reference(const Eigen::VectorXd &u);

    // Barrier stiffness kappa multiplies the barrier sum B (IPC's convention: the
    // incremental potential carries kappa B, not h^2 kappa B).
    void   set_stiffness(double kappa) { kappa_ = kappa; }
    double stiffness() const { return kappa_; }

    // Pairs within dhat at z, and pairs whose boxes swept from z to z + dz (inflated by
    // dhat) overlap: the latter cover every state of the segment.
    CollisionCandidates candidates_at(const Eigen::VectorXd &z) const;
    CollisionCandidates candidates_along(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;

    // Lagged friction: normal forces and tangents from z_lagged, slip measured from z_start.
    void update_friction(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates,
                         const Eigen::VectorXd &z_start);

    // kappa B + D over the candidates' active pairs, +inf on contact.
    double value(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;
    void   add_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates, Eigen::VectorXd &g) const;
    void   add_hessian(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                       std::vector<Eigen::Triplet<double>> &h, bool project) const;
    // Unscaled barrier gradient dB/dz (for the stiffness initialisation).
    Eigen::VectorXd barrier_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;

    // Largest fraction of dz that continuous collision detection certifies.
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz) const;
    double minimum_distance(const Eigen::VectorXd &z) const;  // over all primitive pairs
    bool   has_intersections(const Eigen::VectorXd &z) const;  // crossing primitives
    // Over the candidates' pairs within dhat.
    double active_minimum_distance(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;
    double bbox_diagonal(const Eigen::VectorXd &z) const;

    // Derivatives w.r.t. the body's reference positions u (through the barrier and friction
    // weights, i.e. the reference boundary measures) at state z: gradient g_u (size
    // n_nodes * dim), Hessian H_uu and mixed Hessian H_xu (rows: state z, columns: u).
    struct ReferenceDerivatives
    {
      Eigen::VectorXd                      gu;
      std::vector<Eigen::Triplet<double>> huu, hxu;
    };
    void reference_derivatives(const Eigen::VectorXd &z, const CollisionCandidates &candidates,
                               ReferenceDerivatives &out) const;

    unsigned int n_collision_vertices() const { return surface_.n_vertices; }
    unsigned int n_state_vertices() const { return n_state_vertices_; }
    const contact::CollisionSurface<dim> &surface() const { return surface_; }

  private:
    Eigen::MatrixXd                      collision_positions(const Eigen::VectorXd &z) const;
    std::vector<contact::Constraint>     active_constraints(const Eigen::MatrixXd &V,
                                                            const CollisionCandidates &candidates) const;
    // Adds a collision-vertex gradient / Hessian into state numbering.
    void scatter_gradient(const Eigen::VectorXd &gc, double scale, Eigen::VectorXd &g) const;
    void scatter_hessian(const std::vector<Eigen::Triplet<double>> &hc, double scale,
                         std::vector<Eigen::Triplet<double>> &h) const;

    ContactSettings                 settings_;
    contact::CollisionSurface<dim>  surface_;
    std::vector<int>                state_vertex_;  // collision vertex -> state vertex
    unsigned int                    n_state_vertices_ = 0;
    Eigen::MatrixXd                 rest_positions_;
    Eigen::VectorXd                 reference_;  // body reference positions u
    contact::ConstraintWeights      weights_;
    std::vector<contact::FrictionConstraint<dim>> friction_;
    Eigen::MatrixXd                 friction_start_;
    double                          kappa_ = 0;
    const SimplexMesh<dim>         &mesh_;

    // Body boundary facets (indices into mesh.boundary_facets) whose measure makes up a
    // weight, each with its share (1/dim of a facet per vertex, 1/3 of a face per edge).
    using WeightSources = std::vector<std::pair<unsigned int, double>>;
    const WeightSources &weight_sources(const contact::Constraint &c) const;
    std::vector<WeightSources> vertex_sources_, edge_sources_;
    // Per friction constraint: the weight sources and the normal force per unit weight.
    std::vector<WeightSources> friction_sources_;
    std::vector<double>        friction_unit_force_;
  };
} // namespace ritr
