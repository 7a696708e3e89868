#pragma once
// The switches of r-adaptivity (section Adaptivity of a .prm file), typed. The paper's
// ablations are the non-default values. The *_names tables are the one mapping between
// these values and their names in a parameter file; the *_from() functions throw
// std::invalid_argument for any other name.
#include <ritr/common/enum_names.h>
#include <ritr/terms/inertia_form.h>
#include <ritr/transfer/transfer_integration.h>

#include <string>

namespace ritr
{
  // The outer Hessian: `truncated` drops the implicit response of x like paper eq. 23, but
  // takes d2R/du2 with x following u (ReferenceBlock::following): at fixed x it is three
  // orders of magnitude stiffer than the reduced Hessian and the iteration stalls (Fig. 9
  // rod). It is factorized with a diagonal shift where it is indefinite. `full` adds the
  // implicit response of x, -H_ux H_xx^{-1} H_xu, and projects the result as a whole;
  // `filtered` keeps only the entries of the response dx/du above a relative threshold.
  // Both of the latter are dense: for small meshes and for comparison only. `reduced` applies
  // the exact reduced Hessian matrix-free (reduced_hessian.h) inside a trust-region Newton-CG
  // that follows its negative curvature instead of shifting it away. `quasi_newton` runs the
  // same trust-region iteration on first derivatives alone: the reduced gradient is the
  // partial derivative of R in u at the solved state, and its curvature a limited-memory BFGS
  // approximation (quasi_newton_curvature.h); an outer iteration then costs about one warm
  // inner solve. `automatic`, a scene's default, is resolved by ritr_settings() (time/stepper.h):
  // quasi-newton in dynamics, where the optimal mesh moves little from one step to the next and
  // one cheap outer iteration per step buys the most accuracy per second (doc/benchmarks.md,
  // time to accuracy), and reduced in statics, where every load step needs its mesh converged.
  // `reduced_first` takes the exact reduced Hessian for a step's first outer iteration and the
  // quasi-Newton curvature for the rest: the exact model moves the mesh where the last step's
  // curvature pairs no longer describe R (a body bent into new contact), and the cheap
  // iterations after it refine that mesh (doc/benchmarks.md, Masticator).
  enum class RitrHessian
  {
    automatic,
    truncated,
    full,
    filtered,
    reduced,
    quasi_newton,
    reduced_first
  };

  // The trust-region outer solves (physical admissibility kept at every trial mesh).
  inline bool is_trust_region(const RitrHessian h)
  {
    return h == RitrHessian::reduced || h == RitrHessian::quasi_newton || h == RitrHessian::reduced_first;
  }

  enum class PredictorProjection
  {
    in_optimization,    // eq. 6: pi_t applied at every candidate mesh
    after_optimization  // ablation: nodal values kept during the solve, remapped afterwards
  };

  // Which admissibility conditions r-ITR keeps (paper 4.5, Fig. 8).
  enum class Admissibility
  {
    none,
    geometric,  // boundary sliding, measure barrier, step filter
    physical,   // x = argmin E(., u) at every candidate mesh
    both
  };

  // The transfer's integration as a scene chooses it; automatic: exact on triangles (the
  // objective is then C1 in u), quadrature for rods and tetrahedra.
  enum class TransferIntegrationChoice
  {
    automatic,
    exact,
    quadrature
  };

  inline constexpr EnumNames<TransferIntegrationChoice, 3> transfer_integration_names{
    {{TransferIntegrationChoice::automatic, "auto"},
     {TransferIntegrationChoice::exact, "exact"},
     {TransferIntegrationChoice::quadrature, "quadrature"}}};
  inline constexpr EnumNames<RitrHessian, 7> ritr_hessian_names{{{RitrHessian::automatic, "auto"},
                                                                  {RitrHessian::truncated, "truncated"},
                                                                  {RitrHessian::full, "full"},
                                                                  {RitrHessian::filtered, "filtered"},
                                                                  {RitrHessian::reduced, "reduced"},
                                                                  {RitrHessian::quasi_newton, "quasi-newton"},
                                                                  {RitrHessian::reduced_first, "reduced-first"}}};
  inline constexpr EnumNames<InertiaForm, 2> inertia_form_names{
    {{InertiaForm::corrected, "corrected"}, {InertiaForm::uncorrected, "uncorrected"}}};
  inline constexpr EnumNames<PredictorProjection, 2> predictor_projection_names{
    {{PredictorProjection::in_optimization, "in-optimization"},
     {PredictorProjection::after_optimization, "after-optimization"}}};
  inline constexpr EnumNames<Admissibility, 4> admissibility_names{{{Admissibility::none, "none"},
                                                                    {Admissibility::geometric, "geometric"},
                                                                    {Admissibility::physical, "physical"},
                                                                    {Admissibility::both, "both"}}};

  RitrHessian         ritr_hessian_from(const std::string &name);          // auto|...|reduced|quasi-newton|reduced-first
  InertiaForm         inertia_form_from(const std::string &name);          // corrected|uncorrected
  PredictorProjection predictor_projection_from(const std::string &name);  // in-|after-optimization
  Admissibility       admissibility_from(const std::string &name);         // none|geometric|physical|both
  TransferIntegrationChoice transfer_integration_from(const std::string &name);  // auto|exact|quadrature
} // namespace ritr
