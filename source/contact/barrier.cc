#include <ritr/contact/barrier.h>

#include <algorithm>

namespace ritr::contact
{
  double bbox_diagonal(const Eigen::MatrixXd &V)
  {
    if (V.rows() == 0)
      return 0.0;
    return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  }

  BarrierStiffness initial_barrier_stiffness(const double bbox_diagonal, const double dhat,
                                             const double           average_mass,
                                             const double           average_weight,
                                             const Eigen::VectorXd &grad_energy,
                                             const Eigen::VectorXd &grad_barrier)
  {
    const double dhat_sqr = dhat * dhat;
    double       d_ref    = 1e-8 * bbox_diagonal;
    d_ref *= d_ref;
    if (!(d_ref > 0.0) || d_ref >= dhat_sqr)
      d_ref = 0.5 * dhat_sqr;

    BarrierStiffness s;
    // 4 d b''(d) is the barrier Hessian along the normal in unsquared-distance units.
    s.kappa_min =
      1e11 * average_mass / (average_weight * 4.0 * d_ref * log_barrier_second_derivative(d_ref, dhat_sqr));
    s.kappa_max = 100.0 * s.kappa_min;

    const double gb = grad_barrier.squaredNorm();
    double       kappa = s.kappa_min;
    if (gb > 0.0 && grad_energy.size() == grad_barrier.size())
      {
        const double k = -grad_energy.dot(grad_barrier) / gb;
        if (std::isfinite(k))
          kappa = k;
      }
    s.kappa = std::clamp(kappa, s.kappa_min, s.kappa_max);
    return s;
  }

  double update_barrier_stiffness(const double previous_min_distance, const double min_distance,
                                  const double kappa, const double kappa_max,
                                  const double bbox_diagonal, const double epsilon_scale)
  {
    const double eps = epsilon_scale * bbox_diagonal;
    if (previous_min_distance < eps && min_distance < eps && min_distance < previous_min_distance)
      return std::min(kappa_max, 2.0 * kappa);
    return kappa;
  }
} // namespace ritr::contact
