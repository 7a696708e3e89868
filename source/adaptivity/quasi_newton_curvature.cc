#include <ritr/adaptivity/quasi_newton_curvature.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace ritr
{
  Eigen::VectorXd QuasiNewtonCurvature::product(const Eigen::VectorXd &p, const std::size_t n_pairs) const
  {
    Eigen::VectorXd r = sigma_ * p;
    for (std::size_t i = 0; i < n_pairs; ++i)
      {
        const Pair &q = pairs_[i];
        r += (q.y.dot(p) / q.sy) * q.y - (q.b.dot(p) / q.sb) * q.b;
      }
    return r;
  }

  Eigen::VectorXd QuasiNewtonCurvature::apply(const Eigen::VectorXd &p) const
  {
    Eigen::VectorXd r = product(p, pairs_.size());
    if (barrier_.size() > 0)
      r += barrier_ * p;
    return r;
  }

  void QuasiNewtonCurvature::rebuild()
  {
    for (std::size_t i = 0; i < pairs_.size(); ++i)
      {
        Pair &q = pairs_[i];
        q.b     = product(q.s, i);
        q.sb    = q.s.dot(q.b);
        q.y     = q.measured;
        q.sy    = q.s.dot(q.y);
        // Powell's damping against the approximation this pair updates: y is moved towards
        // b until s . y >= 0.2 s . b, which keeps B positive definite.
        if (q.sy < 0.2 * q.sb)
          {
            const double theta = 0.8 * q.sb / (q.sb - q.sy);
            q.y                = theta * q.y + (1 - theta) * q.b;
            q.sy               = q.s.dot(q.y);
          }
      }
  }

  Eigen::VectorXd QuasiNewtonCurvature::state() const
  {
    const Eigen::Index n = pairs_.empty() ? 0 : pairs_.front().s.size();
    Eigen::VectorXd    state(1 + 2 * n * pairs_.size());
    state[0] = sigma_;
    for (std::size_t i = 0; i < pairs_.size(); ++i)
      state.segment(1 + 2 * n * i, 2 * n) << pairs_[i].s, pairs_[i].measured;
    return state;
  }

  void QuasiNewtonCurvature::restore(const Eigen::VectorXd &state, const Eigen::Index n)
  {
    const bool fits = n > 0 ? state.size() >= 1 && (state.size() - 1) % (2 * n) == 0 &&
                                static_cast<unsigned int>((state.size() - 1) / (2 * n)) <= memory_ :
                              state.size() == 1;
    if (!fits)
      throw std::invalid_argument("not a quasi-Newton curvature of " + std::to_string(n) + " unknowns");
    pairs_.clear();
    for (Eigen::Index offset = 1; offset < state.size(); offset += 2 * n)
      {
        const Eigen::VectorXd s = state.segment(offset, n), y = state.segment(offset + n, n);
        pairs_.push_back({s, y, y, Eigen::VectorXd(), s.dot(y), 0.0});
      }
    sigma_ = state[0];
    rebuild();
  }

  bool QuasiNewtonCurvature::update(const Eigen::VectorXd &s, const Eigen::VectorXd &y)
  {
    const double ss = s.squaredNorm(), yy = y.squaredNorm(), sy = s.dot(y);
    if (!(ss > 0) || !(yy > 0) || !std::isfinite(sy))
      return false;
    // The base scale of the newest pair: its curvature along s where R curves up along it (the
    // Rayleigh quotient y.y / s.y of the Hessian's mean over the step), else its largest scale.
    sigma_ = sy > 0 ? yy / sy : std::sqrt(yy / ss);
    pairs_.push_back({s, y, y, Eigen::VectorXd(), sy, 0.0});
    if (pairs_.size() > memory_)
      pairs_.pop_front();
    rebuild();
    return true;
  }
} // namespace ritr
