#pragma once
// Which inertia energy a step minimises (paper section 4.3).
namespace ritr
{
  enum class InertiaForm
  {
    corrected,   // eq. 10: 1/2 x^T M x - x^T M x_pred
    uncorrected  // eq. 8 (ablation): adds 1/2 x_pred^T M x_pred, which biases the mesh
  };
} // namespace ritr
