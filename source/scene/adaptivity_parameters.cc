// Subsection Adaptivity of a parameter file.
#include <ritr/scene/parameter_text.h>
#include <ritr/scene/scene.h>

#include <deal.II/base/parameter_handler.h>

namespace ritr
{
  void AdaptivityScene::declare_parameters(dealii::ParameterHandler &prm)
  {
    namespace Patterns = dealii::Patterns;
    const AdaptivityScene d;
    prm.enter_subsection("Adaptivity");
    prm.declare_entry("enabled", prm_value(d.enabled), Patterns::Bool(), "Optimal r-adaptive in-timestep remeshing: every step also optimises the reference node positions (one density for all bodies; Dirichlet nodes keep their reference position unless their condition has sliding reference nodes).");
    prm.declare_entry("hessian", name_of(ritr_hessian_names, d.hessian), Patterns::Selection(selection(ritr_hessian_names)), "Outer Hessian. auto: quasi-newton in dynamics, reduced in statics. truncated (per-cell PSD blocks of d2R/du2, paper eq. 23), full (dense Schur complement with the response of x) or filtered (that response with entries below 1e-3 of the largest dropped), each with backtracking on R; full and filtered are dense, for small meshes. reduced: the exact Schur complement applied matrix-free (one sparse factorization of H_xx per iteration) in a trust-region Newton-CG that follows negative curvature, with trial states predicted by the implicit-function response of x. quasi-newton: the same trust region on first derivatives only (the reduced gradient is the partial derivative of R in u at the solved state; its curvature a limited-memory BFGS kept across steps), with trial states carried by the current deformation; an outer iteration costs about one warm inner solve. reduced-first: reduced for a step's first outer iteration, quasi-newton for the rest.");
    prm.declare_entry("inertia", name_of(inertia_form_names, d.inertia), Patterns::Selection(selection(inertia_form_names)), "Inertia term: corrected (paper eq. 10) or uncorrected (eq. 8, keeps 1/2 x_pred^T M x_pred; ablation).");
    prm.declare_entry("projection", name_of(predictor_projection_names, d.projection), Patterns::Selection(selection(predictor_projection_names)), "L2 projection of the predictor: at every candidate mesh (eq. 6) or only after the step's optimisation (ablation).");
    prm.declare_entry("admissibility", name_of(admissibility_names, d.admissibility), Patterns::Selection(selection(admissibility_names)), "geometric: boundary sliding, measure barrier and step filter; physical: x = argmin E(., u) at every mesh (without it x and u are minimised jointly; no contact). Ablation switch of paper Fig. 8.");
    prm.declare_entry("measure barrier stiffness", prm_value(d.measure_barrier_stiffness), Patterns::Double(0), "Stiffness of the reference area/volume barrier (eq. 21); 0: the contact barrier's stiffness, or (h^2) E / w_hat without contact.");
    prm.declare_entry("quadrature subdivisions", prm_value(d.quadrature_subdivisions), Patterns::Integer(0), "Transfer quadrature on each candidate cell: the Witherden-Vincent rule of 5 points per direction, repeated on n^dim sub-cells (the predictor has kinks inside candidate cells, and the outer solve exploits quadrature error). 0: 64 for rods, 1 for triangles and tetrahedra.");
    prm.declare_entry("transfer integration", name_of(transfer_integration_names, d.transfer_integration), Patterns::Selection(selection(transfer_integration_names)), "How the L2 transfer of the predictor is integrated. exact: on the intersection of the candidate and the old mesh (triangles only), so that R is C1 in the reference positions; quadrature: the paper's fixed rule on each candidate cell (see quadrature subdivisions), whose gradient jumps wherever a point crosses an old edge. auto: exact for triangles, quadrature for rods and tetrahedra.");
    prm.declare_entry("epsilon r", prm_value(d.epsilon_r), Patterns::Double(0), "Outer tolerance on |du|_inf relative to the mesh's bounding-box diagonal; smaller adapts more.");
    prm.declare_entry("sliding tolerance", prm_value(d.sliding_tolerance), Patterns::Double(0), "eps_b: boundary nodes slide in facets whose normals agree within 1 - n.n <= eps_b (and along straight 3D edges).");
    prm.declare_entry("decrease tolerance", prm_value(d.decrease_tolerance), Patterns::Double(0), "hessian = reduced, quasi-newton or reduced-first: a step also ends (outer_stop small_decrease) once the model predicts a decrease of R below this fraction of the decrease the step has already made; 0: the square root of epsilon r (1e-2 for 1e-4), so that epsilon r stays the one knob.");
    prm.declare_entry("max iterations", prm_value(d.max_iterations), Patterns::Integer(0), "Outer iterations per step; 0: 1 in dynamics (the defaults' time to accuracy, doc/benchmarks.md), 100 in statics.");
    prm.declare_entry("carry trust region", prm_value(d.carry_trust_region), Patterns::Bool(), "hessian = reduced: each step's outer trust region starts with the radius the last step ended with (quasi-newton's and reduced-first's always do), not at half the smallest initial cell. With one outer iteration per step in dynamics the mesh can then follow the body by more than half a cell per step (doc/benchmarks.md, Masticator).");
    prm.declare_entry("model tolerance", prm_value(d.model_tolerance), Patterns::Double(1e-12, 0.9), "hessian = reduced, quasi-newton or reduced-first: the largest residual, relative to the outer gradient, to which CG solves the outer model's Newton equation inside the trust region (it tightens as sqrt(|g| / |g_0|) over a step's outer iterations). A loose model solve costs fewer products with the reduced Hessian (each a solve with H_xx) and stops on the directions CG finds first (doc/benchmarks.md, Masticator).");
    prm.declare_entry("inner tolerance factor", prm_value(d.inner_tolerance_factor), Patterns::Double(1), "hessian = reduced, quasi-newton or reduced-first: inexact inner solves. A trial mesh's Newton tolerance is Solver/newton tolerance times min(this, |du|_inf / epsilon r), so it tightens as the outer step converges; a step whose accepted state was solved more loosely goes on with tight solves from a tight one at its mesh. 1: every inner solve tight.");
    prm.declare_entry("trial iterations", prm_value(d.trial_iterations), Patterns::Integer(0), "hessian = reduced, quasi-newton or reduced-first: inexact inner solves. A trial mesh's Newton stops after this many iterations even short of its tolerance (E there bounds its minimum from above, so an accepted trial still lowers R); a step whose accepted state was solved short of the tolerance goes on with tight solves from a tight one at its mesh. 0: every trial solved to its tolerance.");
    prm.leave_subsection();
  }

  // The patterns admit only the names of the tables.
  void AdaptivityScene::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptivity");
    enabled                   = prm.get_bool("enabled");
    hessian                   = ritr_hessian_from(prm.get("hessian"));
    inertia                   = inertia_form_from(prm.get("inertia"));
    projection                = predictor_projection_from(prm.get("projection"));
    admissibility             = admissibility_from(prm.get("admissibility"));
    measure_barrier_stiffness = prm.get_double("measure barrier stiffness");
    quadrature_subdivisions   = prm.get_integer("quadrature subdivisions");
    transfer_integration      = transfer_integration_from(prm.get("transfer integration"));
    epsilon_r                 = prm.get_double("epsilon r");
    decrease_tolerance        = prm.get_double("decrease tolerance");
    inner_tolerance_factor    = prm.get_double("inner tolerance factor");
    trial_iterations          = prm.get_integer("trial iterations");
    sliding_tolerance         = prm.get_double("sliding tolerance");
    max_iterations            = prm.get_integer("max iterations");
    carry_trust_region        = prm.get_bool("carry trust region");
    model_tolerance           = prm.get_double("model tolerance");
    prm.leave_subsection();
  }
} // namespace ritr
