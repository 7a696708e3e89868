#pragma once
// A scene as read from a .prm file: everything a simulation needs, validated, with no
// deal.II types in it. Expressions (initial velocity, Dirichlet displacement, obstacle
// motion) stay strings here and are compiled by deal.II's FunctionParser where used.
// The default member values are the defaults of the .prm file: every subsection declares its
// entries from a default-constructed struct (deal.II step-44's declare_parameters), the
// numbered ones (Body, Material, Dirichlet, Obstacle) and the top level in parameters.cc.
// An expression left empty here is zero, spelled "0;0;0" (any dimension) in the file.
#include <ritr/elasticity/material.h>
#include <ritr/mesh/mesh_builder.h>
#include <ritr/adaptivity/ritr_options.h>
#include <ritr/solver/distributed_solver.h>
#include <ritr/solver/hessian_projection.h>

#include <map>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace ritr
{
  // The scene lists only the enabled bodies, conditions and obstacles; `section` keeps the
  // name of each one's .prm subsection ("Body 2") for messages.
  struct BodyScene
  {
    BodyDescription geometry;
    std::string     initial_velocity;  // vector expression in x,y,z ("0; -1")
    std::string     section;
  };

  struct DirichletScene
  {
    std::vector<unsigned int> boundary_ids;  // nodes on these boundary facets
    std::string               region;        // or nodes where this expression in x,y,z > 0
    std::string               displacement;  // vector expression in x,y,z,t
    std::string               section;
    // r-ITR: the condition's boundary nodes slide along it, carrying it to the material
    // points they move to (x = u + displacement; the displacement must be uniform).
    bool                      sliding_reference_nodes = false;
  };

  struct ObstacleScene
  {
    std::string         type = "none";  // none|plane|box|spikes|punch|file
    std::string         file;  // .obj (3D triangles / 2D lines) or .msh surface
    std::vector<double> point{0, 0, 0};   // plane point, box/punch centre, first spike tip base
    std::vector<double> normal{0, 1, 0};  // plane normal
    std::vector<double> size{10, 10, 10};  // plane extent / box and punch size / spikes row extent
    unsigned int        count = 5;        // spikes
    double              spike_height = 0.2;
    std::string         translation;       // vector expression in t; empty: none
    std::string         rotation_angle;    // scalar expression in t (radians); empty: none
    std::vector<double> rotation_axis{0, 0, 1};
    std::vector<double> rotation_center{0, 0, 0};
    std::string         section;
  };

  struct ContactScene
  {
    bool        enabled              = true;
    double      dhat                 = 1e-3;
    double      barrier_stiffness    = 0;  // 0: adaptive (IPC's rule)
    double      friction_coefficient = 0;
    double      epsilon_v            = 1e-3;
    unsigned    friction_iterations  = 1;
    bool        self_contact         = true;

    // Subsection Contact: its entries declared with this struct's values as defaults, and
    // parsed into it. parse_parameters throws EntryError for a value no pattern rejects.
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);
  };

  // Optimal r-adaptive in-timestep remeshing (paper Algorithm 1).
  struct AdaptivityScene
  {
    bool        enabled           = false;
    RitrHessian         hessian       = RitrHessian::automatic;
    InertiaForm         inertia       = InertiaForm::corrected;
    PredictorProjection projection    = PredictorProjection::in_optimization;
    Admissibility       admissibility = Admissibility::both;
    double      epsilon_r         = 1e-6;         // on |du|_inf, in units of the mesh's size
    double      decrease_tolerance = 0;           // reduced Hessian: on the predicted decrease of R; 0: sqrt(epsilon_r)
    double      inner_tolerance_factor = 1;       // trust region: trials' inner tolerance up to this times looser
    unsigned    trial_iterations  = 0;            // trust region: Newton iterations per trial's inner solve; 0: all
    double      sliding_tolerance = 1e-6;         // eps_b
    double      measure_barrier_stiffness = 0;    // 0: automatic
    unsigned    quadrature_subdivisions   = 0;    // composite transfer rule; 0: automatic
    TransferIntegrationChoice transfer_integration = TransferIntegrationChoice::automatic;
    unsigned    max_iterations    = 0;    // 0: 1 in dynamics, 100 in statics
    bool        carry_trust_region = false;  // reduced: each step's region starts where the last ended
    double      model_tolerance    = 1e-2;   // trust region: CG's relative residual on the outer model, at most

    // Subsection Adaptivity: its entries declared with this struct's values as defaults, and
    // parsed into it. parse_parameters throws EntryError for a value no pattern rejects.
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);
  };

  struct SolverScene
  {
    double       newton_tolerance = 1e-5;  // dynamics: on |dx|_inf / h (velocity units)
    double       static_tolerance = 1e-8;  // statics: on |dx|_inf / bounding-box diagonal
    unsigned int max_iterations   = 200;
    unsigned int threads          = 0;  // 0: all cores
    unsigned int factorization_threads = 1;  // BLAS threads in large factorizations
    bool         newton_log       = false;  // newton.csv: one row per Newton iteration
    HessianProjection hessian_projection = HessianProjection::trust_region;
    DistributedSolver distributed_solver = DistributedSolver::amg;  // runs under mpirun

    // Subsection Solver: its entries declared with this struct's values as defaults, and
    // parsed into it. parse_parameters throws EntryError for a value no pattern rejects.
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);
  };

  struct Scene
  {
    std::string parameter_file;
    int         dimension = 2;
    std::string mode      = "dynamic";  // dynamic | static
    double      time_step = 0.01;
    double      end_time  = 1.0;
    std::string output_directory = "output";
    unsigned    output_every     = 1;
    bool        write_nodal_csv  = false;
    // Another run's frame to start from (resolved against the .prm file; empty: none), and the
    // time the run starts at: 0, or that frame's (set when the problem is built).
    std::string start_from;
    double      start_time = 0;

    std::vector<BodyScene>      bodies;
    std::vector<Material>       materials;  // indexed by material id
    std::vector<double>         gravity{0, -9.81, 0};
    std::string                 load_factor = "1";  // scalar expression in t
    std::vector<DirichletScene> dirichlet;
    std::vector<ObstacleScene>  obstacles;
    ContactScene                contact;
    SolverScene                 solver;
    AdaptivityScene             adaptivity;

    // The line of each entry set in the parameter file ("Body 0/radius" -> 12).
    std::map<std::string, unsigned int> entry_lines;
    // "set Section/entry = value" for every entry whose value as parsed differs from its default,
    // one per line, but for the output directory, the thread counts and the end time: what makes
    // two scenes the same run (checkpoints refuse another scene's), whatever the file's comments
    // and layout, and whatever entries a newer ritr adds with defaults that keep its results.
    std::string parameter_listing;

    bool dynamic() const { return mode == "dynamic"; }
    unsigned int n_steps() const;
    // The start of a message about `entry`: "FILE:LINE: ENTRY", or "FILE: ENTRY" when the
    // entry is not set in the file.
    std::string where(const std::string &entry) const;
  };
} // namespace ritr
