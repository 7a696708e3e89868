#include <ritr/solver/steihaug_cg.h>

#include <cmath>

namespace ritr
{
  SteihaugResult steihaug_cg(const LinearMap &apply, const Eigen::VectorXd &g, const double radius,
                             const double tolerance, const unsigned int max_iterations, const LinearMap &metric,
                             const LinearMap &precondition)
  {
    const auto M    = [&](const Eigen::VectorXd &v) { return metric ? metric(v) : v; };
    const auto Minv = [&](const Eigen::VectorXd &v) { return precondition ? precondition(v) : v; };
    // tau >= 0 with |p + tau d|_M = radius (p inside the region).
    const auto to_boundary = [&](const Eigen::VectorXd &p, const Eigen::VectorXd &d) {
      const Eigen::VectorXd md = M(d);
      const double dd = d.dot(md), pd = p.dot(md), pp = p.dot(M(p));
      return (-pd + std::sqrt(std::max(pd * pd + dd * (radius * radius - pp), 0.0))) / dd;
    };

    SteihaugResult result;
    Eigen::VectorXd p = Eigen::VectorXd::Zero(g.size()), residual = g, z = Minv(residual), d = -z;
    // The model's change is tracked along the way: m(p + a d) = m(p) + a r.d + a^2/2 d.S d.
    double model = 0, rz = residual.dot(z);
    const auto finish = [&](const Eigen::VectorXd &step, const double change) {
      result.step             = step;
      result.predicted_change = change;
      return result;
    };
    if (residual.norm() <= tolerance)
      {
        result.interior = true;
        return finish(p, 0.0);
      }
    for (; result.iterations < max_iterations;)
      {
        const Eigen::VectorXd sd = apply(d);
        ++result.iterations;
        const double curvature = d.dot(sd), slope = residual.dot(d);
        if (curvature <= 0)
          {
            result.negative_curvature = true;
            const double tau = to_boundary(p, d);
            return finish(p + tau * d, model + tau * slope + 0.5 * tau * tau * curvature);
          }
        const double          a    = rz / curvature;
        const Eigen::VectorXd next = p + a * d;
        if (next.dot(M(next)) >= radius * radius)
          {
            const double tau = to_boundary(p, d);
            return finish(p + tau * d, model + tau * slope + 0.5 * tau * tau * curvature);
          }
        p = next;
        model += a * slope + 0.5 * a * a * curvature;
        residual += a * sd;
        if (residual.norm() <= tolerance)
          {
            result.interior = true;
            return finish(p, model);
          }
        z                    = Minv(residual);
        const double rz_next = residual.dot(z);
        d                    = -z + (rz_next / rz) * d;
        rz                   = rz_next;
      }
    return finish(p, model);  // inside, but not converged to the tolerance
  }
} // namespace ritr
