#pragma once
// Conservative continuous collision detection for linear trajectories V0 -> V1, by
// Additive CCD (Li et al. 2021, "Codimensional Incremental Potential Contact").
//
// Per pair: with displacements p_i made relative to their mean (distance is translation
// invariant), the distance can shrink at most at rate l_p = max_A |p_i| + max_B |p_j| (A,
// B the two primitives' vertices). Stepping by (current distance - margin) / l_p is
// therefore safe; the distance is re-evaluated after each step, so the steps grow when the
// motion is not head-on. Variant used here, with s = min_separation_fraction and d0 the
// start distance:
//   - every returned t has d(t) >= s d0, and d >= s d0 / 2 along the whole segment [0, t];
//   - the first step goes exactly to the bound d >= s d0, later steps to d >= s d0 / 2,
//     stopping (returning the previous t) as soon as d < s d0.
// 1D vertex-vertex pairs are solved analytically (largest t with |d(t)| >= s d0).
#include <ritr/contact/broad_phase.h>
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/distance.h>

#include <Eigen/Core>

namespace ritr::contact
{
  // Largest safe fraction t in [0, t_max] of the step x0 -> x1 for one primitive pair
  // (stencil ordering as in distance.h). Returns 0 if the pair already touches at x0. After
  // max_iterations steps the current (safe) t is returned.
  template <int dim>
  double additive_ccd(ContactKind kind, const StencilVector<dim> &x0,
                      const StencilVector<dim> &x1, double min_separation_fraction = 0.1,
                      double t_max = 1.0, long max_iterations = 1000000);

  // Largest step t in [0, 1] along V0 -> V1 (both n x dim; obstacle vertices move by
  // their script) such that every pair whose swept boxes come closer than `inflation`
  // keeps d(t) >= min_separation_fraction * d(0); all other pairs stay farther apart than
  // `inflation` throughout. Hence no distance is ever <= 0 at t (given positive start
  // distances). Pass inflation = dhat to also keep the fraction for every pair that could
  // enter the barrier's range.
  template <int dim>
  double max_step(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V0,
                  const Eigen::MatrixXd &V1, double min_separation_fraction = 0.1,
                  double inflation = 0.0);
  // The same over pairs already found: `candidates` are find_candidates(surface, V0, V1,
  // inflation), for callers that need them for the energy along the step as well.
  template <int dim>
  double max_step(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V0,
                  const Eigen::MatrixXd &V1, const std::vector<Candidate> &candidates,
                  double min_separation_fraction);
} // namespace ritr::contact
