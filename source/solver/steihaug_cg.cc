#include <ritr/solver/steihaug_cg.h>

#include <cmath>

namespace ritr
{
  SteihaugResult steihaug_cg(const LinearMap &apply, const Eigen::VectorXd &g, const double radius,
                             const double tolerance, const unsigned int max_iterations,
                             const LinearMap &precondition)
  {
    const auto Minv = [&](const Eigen::VectorXd &v) { return precondition ? precondition(v) : v; };

    SteihaugResult result;
    Eigen::VectorXd p = Eigen::VectorXd::Zero(g.size()), residual = g, z = Minv(residual), d = -z;
    // The model's change is tracked along the way: m(p + a d) = m(p) + a r.d + a^2/2 d.S d.
    // So are the M-inner products of p and d (Gould, Lucidi, Roma and Toint 1999): with z =
    // M^-1 r, d.M d = r.z + beta^2 d.M d and p.M d = beta (p.M d + a d.M d), which saves two
    // products with M per iteration.
    double model = 0, rz = residual.dot(z), pMp = 0, pMd = 0, dMd = rz;
    // tau >= 0 with |p + tau d|_M = radius (p inside the region).
    const auto to_boundary = [&]() { return fraction_to_boundary(pMp, pMd, dMd, radius); };
    const auto finish = [&](const Eigen::VectorXd &step, const double change, const double step_norm_squared) {
      result.step             = step;
      result.predicted_change = change;
      result.metric_norm      = std::sqrt(std::max(step_norm_squared, 0.0));
      return result;
    };
    const auto finish_on_boundary = [&](const double slope, const double curvature) {
      const double tau = to_boundary();
      return finish(p + tau * d, model + tau * slope + 0.5 * tau * tau * curvature, radius * radius);
    };
    if (residual.norm() <= tolerance)
      {
        result.interior = true;
        return finish(p, 0.0, 0.0);
      }
    for (; result.iterations < max_iterations;)
      {
        const Eigen::VectorXd sd = apply(d);
        ++result.iterations;
        const double curvature = d.dot(sd), slope = residual.dot(d);
        if (curvature <= 0)
          {
            result.negative_curvature = true;
            return finish_on_boundary(slope, curvature);
          }
        const double a        = rz / curvature;
        const double next_pMp = pMp + 2 * a * pMd + a * a * dMd;
        if (next_pMp >= radius * radius)
          return finish_on_boundary(slope, curvature);
        p += a * d;
        pMp = next_pMp;
        model += a * slope + 0.5 * a * a * curvature;
        residual += a * sd;
        if (residual.norm() <= tolerance)
          {
            result.interior = true;
            return finish(p, model, pMp);
          }
        z                    = Minv(residual);
        const double rz_next = residual.dot(z), beta = rz_next / rz;
        pMd                  = beta * (pMd + a * dMd);
        dMd                  = rz_next + beta * beta * dMd;
        d                    = -z + beta * d;
        rz                   = rz_next;
      }
    return finish(p, model, pMp);  // inside, but not converged to the tolerance
  }
} // namespace ritr
