#pragma once
// The problem a scene describes, built once before the first step: the mesh and its
// materials, the rigid obstacles and their scripted motion, the Dirichlet conditions, the
// collision geometry (only when contact is on), the terms of every step's energy, and the
// initial state. make_problem() checks everything that can be checked before a step runs,
// so that bad input fails here with an InputError naming the .prm entry, never later as a
// failed step.
#include <ritr/common/simplex_quadrature.h>
#include <ritr/contact/collision_mesh.h>
#include <ritr/elasticity/cell_materials.h>
#include <ritr/scene/expression.h>
#include <ritr/scene/scene.h>
#include <ritr/terms/term_sum.h>

#include <array>
#include <memory>
#include <optional>

namespace ritr
{
  template <int dim>
  class Problem
  {
  public:
    // Use make_problem(); the terms keep references to the mesh, so a problem never moves.
    Problem(const Problem &) = delete;
    Problem &operator=(const Problem &) = delete;

    Scene                                    scene;
    SimplexMesh<dim>                         mesh;
    std::unique_ptr<CellMaterials<dim>>      materials;
    std::vector<contact::RigidObstacle<dim>> obstacles;
    std::unique_ptr<CollisionMesh<dim>>      collisions;  // empty when contact is off
    // The terms of E and R as the scene asks for them (problem_terms.cc): inertia (transferred
    // with r-adaptivity), elasticity, body forces, contact barrier and friction, and with
    // r-adaptivity the reference measure barrier.
    std::unique_ptr<TermSum<dim>>            terms;
    // A run shared among processes (parallel/work_share.h): who owns which nodes, cells and
    // stencils. The cell terms are built on `owned_mesh` (the whole mesh's nodes, this
    // process's cells) and its materials; serial runs leave both empty and build them on the
    // whole mesh.
    WorkShare                                work_share;
    SimplexMesh<dim>                         owned_mesh;
    std::unique_ptr<CellMaterials<dim>>      owned_materials;
    std::vector<bool>                        kinematic;  // prescribed state entries
    // Dirichlet nodes whose condition lets r-ITR slide them (`sliding reference nodes`), with
    // their condition, and that entry of the first such condition (for errors).
    std::vector<std::pair<unsigned int, unsigned int>> sliding_dirichlet_nodes;  // node, condition
    std::string                              sliding_dirichlet_entry;

    // The initial state: reference and deformed body nodes, their velocity, and the obstacle
    // vertices (the state is z = [x, obstacle vertices]).
    Eigen::VectorXd initial_reference, initial_positions, initial_velocity, initial_obstacle_positions;

    // The prescribed state entries at time t (Dirichlet nodes, then obstacle vertices; other
    // entries zero). Throws InputError naming the expression that is not finite at t.
    Eigen::VectorXd targets(double t) const;
    // The body force per unit mass at time t, load factor applied; throws InputError when the
    // load factor is not finite at t.
    std::array<double, dim> gravity(double t) const;
    // The rule that integrates r-adaptivity's L2 transfer on candidate cells.
    SimplexQuadrature<dim> transfer_quadrature() const;
    // The scene's transfer integration for this dimension; throws InputError for exact
    // integration outside 2D.
    transfer::TransferIntegration transfer_integration() const;

  private:
    Problem() = default;
    template <int d>
    friend std::unique_ptr<Problem<d>> make_problem(const Scene &scene, const WorkShare &share);

    void build_mesh_and_materials();
    void set_initial_velocity();
    void build_obstacles();
    void build_dirichlet_conditions();
    // start_frame.cc: the state, and the start time, of the frame `start from` names.
    void start_from_frame();
    void build_contact();
    // The cells this process assembles (all of them in a serial run).
    void share_cells();
    void build_terms();
    // initial_state.cc: the initial state's checks, each naming the body or obstacle at fault.
    void        check_initial_state() const;
    void        check_coordinates() const;
    void        check_element_measures() const;
    void        check_separation(const Eigen::VectorXd &z) const;      // crossing or touching
    void        check_nothing_inside(const Eigen::VectorXd &z) const;  // inside a body or closed obstacle
    // The .prm subsection ("Body 1", "Obstacle 0") of a vertex of the state z.
    std::string name_of_state_vertex(int vertex) const;

    std::vector<std::pair<unsigned int, unsigned int>> dirichlet_nodes_;  // node, condition
    std::vector<Expression<dim>>                       dirichlet_displacements_;
    std::vector<std::string>                           dirichlet_entries_;  // "FILE:LINE: Dirichlet 0/displacement"
    std::optional<Expression<dim>>                     load_factor_;
  };

  // Builds and checks the problem of `scene`; throws InputError on bad input. With a share
  // of more than one process, its work is split among them (fixed meshes only).
  template <int dim>
  std::unique_ptr<Problem<dim>> make_problem(const Scene &scene, const WorkShare &share = WorkShare());
} // namespace ritr
