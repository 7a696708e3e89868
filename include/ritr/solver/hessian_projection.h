#pragma once
#include <ritr/common/enum_names.h>

namespace ritr
{
  // Which Hessian a Newton step solves with. Projecting every element and contact stencil
  // onto the PSD cone (IPC's projected Newton) gives a descent direction that rarely runs
  // into contact, but a different model of the energy wherever stencils are indefinite: near
  // a sharp punch corner Newton then crawls linearly for thousands of iterations, where the
  // exact Hessian converges quadratically -- and fails elsewhere (doc/method.md).
  enum class HessianProjection
  {
    always,   // projected Newton
    never,    // exact Hessian, shifted by a multiple of the identity where indefinite
    adaptive,  // projected until full steps stop shrinking, then exact; projected again for
               // the rest of the solve if an exact step's line search fails
    // The exact Hessian in a trust region, the subproblem solved by Steihaug's CG
    // preconditioned with the projected Hessian's factor (projected line-search steps while
    // prescribed entries still move): negative curvature is followed to the region's edge
    // instead of being shifted away, and where no stencil is indefinite CG ends in one
    // iteration on the projected Newton step.
    trust_region
  };

  // Their names in a parameter file (Solver/hessian projection).
  inline constexpr EnumNames<HessianProjection, 4> hessian_projection_names{{{HessianProjection::always, "always"},
                                                                             {HessianProjection::never, "never"},
                                                                             {HessianProjection::adaptive, "adaptive"},
                                                                             {HessianProjection::trust_region, "trust-region"}}};
} // namespace ritr
