#pragma once
// The curvature of the outer objective u -> R(x(u), u) that an outer trust-region model
// takes, in the sliding basis: the exact reduced Hessian (reduced_hessian.h) or a
// quasi-Newton approximation of it (quasi_newton_curvature.h). Either includes the measure
// barrier's Hessian at the model's point, which the model replaces by the barrier itself
// (outer_model.h).
#include <Eigen/Core>

namespace ritr
{
  class OuterCurvature
  {
  public:
    virtual ~OuterCurvature() = default;
    // The curvature times p, p in basis coordinates.
    virtual Eigen::VectorXd apply(const Eigen::VectorXd &p) const = 0;
  };
} // namespace ritr
