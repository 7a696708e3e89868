// Subsection Solver of a parameter file.
#include <ritr/scene/parameter_text.h>
#include <ritr/scene/scene.h>

#include <deal.II/base/parameter_handler.h>

namespace ritr
{
  void SolverScene::declare_parameters(dealii::ParameterHandler &prm)
  {
    namespace Patterns = dealii::Patterns;
    const SolverScene d;
    prm.enter_subsection("Solver");
    prm.declare_entry("newton tolerance", prm_value(d.newton_tolerance), Patterns::Double(0), "Dynamics: stop when |dx|_inf / h < this times the bodies' bounding-box diagonal (eps_e, velocity relative to the scene's size).");
    prm.declare_entry("static tolerance", prm_value(d.static_tolerance), Patterns::Double(0), "Statics: stop when |dx|_inf < this times the bodies' bounding-box diagonal.");
    prm.declare_entry("max iterations", prm_value(d.max_iterations), Patterns::Integer(1), "Newton iterations per solve before the run stops (exit code 3); such a run resumes (--resume) with a larger value.");
    prm.declare_entry("hessian projection", name_of(hessian_projection_names, d.hessian_projection), Patterns::Selection(selection(hessian_projection_names)), "always: projected Newton (every element and contact stencil's Hessian projected onto the PSD cone, as in IPC; it converges only linearly where the projected Hessian differs much from the exact one, as under a sharp punch on a fine mesh); never: the exact Hessian, shifted by a multiple of the identity where it is not positive definite (quadratic convergence there, but its steps run into contact and get cut back by CCD: slower or failing on dynamic contact scenes); adaptive: projected Newton until five full steps in a row fail to halve, then the exact Hessian (projected again, for the rest of the solve, if an exact step's line search fails); trust-region: the exact Hessian in a trust region, its subproblem solved by CG preconditioned with the projected Hessian's factor, which follows negative curvature instead of shifting it away (projected line-search steps while prescribed entries still move).");
    prm.declare_entry("distributed solver", name_of(distributed_solver_names, d.distributed_solver), Patterns::Selection(selection(distributed_solver_names)), "A fixed-mesh run under mpirun (mpirun -np N ritr SCENE.prm) solves its Newton systems with Trilinos: amg: conjugate gradients preconditioned by algebraic multigrid (ML); direct: a distributed sparse LU (Amesos with MUMPS), slower than amg on two processes on the 2D and 3D meshes of 54K-101K vertices measured (doc/parallel.md). With direct the trust region runs as in a serial run (MUMPS' factor preconditions its CG); with amg trust-region becomes always (one V-cycle is too loose a preconditioner for it); never and adaptive run on one process only.");
    prm.declare_entry("threads", prm_value(d.threads), Patterns::Integer(0), "Assembly threads (0: all cores; on several processes, the cores shared among them).");
    prm.declare_entry("factorization threads", prm_value(d.factorization_threads), Patterns::Integer(1), "BLAS threads in a Cholesky factorization of at least 1e10 flops (3D meshes from about 40K vertices; smaller ones do not gain). 1 keeps every result bit-identical on any number of assembly threads; more factorize faster on large 3D meshes (doc/benchmarks.md), with results that differ at round-off.");
    prm.declare_entry("newton log", prm_value(d.newton_log), Patterns::Bool(), "Also write newton.csv: one row per Newton iteration (energy, step and gradient norms, predicted decrease, CCD bound, accepted step, barrier stiffness, closest active distance), for diagnosing slow or failed solves.");
    prm.leave_subsection();
  }

  // The pattern admits only the names of hessian_projection_names.
  void SolverScene::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    newton_tolerance   = prm.get_double("newton tolerance");
    static_tolerance   = prm.get_double("static tolerance");
    max_iterations     = prm.get_integer("max iterations");
    threads            = prm.get_integer("threads");
    factorization_threads = prm.get_integer("factorization threads");
    newton_log         = prm.get_bool("newton log");
    hessian_projection = value_named(hessian_projection_names, prm.get("hessian projection"), "Hessian projection");
    distributed_solver = value_named(distributed_solver_names, prm.get("distributed solver"), "distributed solver");
    prm.leave_subsection();
  }
} // namespace ritr
