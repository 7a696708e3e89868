#include <ritr/solver/steihaug_cg.h>

#include <cmath>

namespace ritr
{
  namespace
  {
    // tau >= 0 with |p + tau d| = radius (p inside the region).
    double to_boundary(const Eigen::VectorXd &p, const Eigen::VectorXd &d, const double radius)
    {
      const double dd = d.squaredNorm(), pd = p.dot(d), pp = p.squaredNorm();
      const double discriminant = std::max(pd * pd + dd * (radius * radius - pp), 0.0);
      return (-pd + std::sqrt(discriminant)) / dd;
    }
  } // namespace

  SteihaugResult steihaug_cg(const std::function<Eigen::VectorXd(const Eigen::VectorXd &)> &apply,
                             const Eigen::VectorXd &g, const double radius, const double tolerance,
                             const unsigned int max_iterations)
  {
    SteihaugResult result;
    Eigen::VectorXd p = Eigen::VectorXd::Zero(g.size()), residual = g, d = -g;
    // The model's change is tracked along the way: m(p + a d) = m(p) + a r.d + a^2/2 d.S d.
    double model = 0, rr = residual.squaredNorm();
    const auto finish = [&](const Eigen::VectorXd &step, const double change) {
      result.step             = step;
      result.predicted_change = change;
      return result;
    };
    if (std::sqrt(rr) <= tolerance)
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
            const double tau = to_boundary(p, d, radius);
            return finish(p + tau * d, model + tau * slope + 0.5 * tau * tau * curvature);
          }
        const double a = rr / curvature;
        if ((p + a * d).norm() >= radius)
          {
            const double tau = to_boundary(p, d, radius);
            return finish(p + tau * d, model + tau * slope + 0.5 * tau * tau * curvature);
          }
        p += a * d;
        model += a * slope + 0.5 * a * a * curvature;
        residual += a * sd;
        const double rr_next = residual.squaredNorm();
        if (std::sqrt(rr_next) <= tolerance)
          {
            result.interior = true;
            return finish(p, model);
          }
        d  = -residual + (rr_next / rr) * d;
        rr = rr_next;
      }
    return finish(p, model);  // inside, but not converged to the tolerance
  }
} // namespace ritr
