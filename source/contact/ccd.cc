#include <ritr/contact/broad_phase.h>
#include <ritr/contact/ccd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ritr::contact
{
  namespace
  {
    // 1D: d(t) = |r0 + t dr|; largest t <= t_max with |d(t)| >= s |r0| along [0, t].
    double vertex_vertex_ccd_1d(const double r0, const double dr, const double s,
                                const double t_max)
    {
      const double d0 = std::abs(r0);
      if (d0 <= 0.0)
        return 0.0;
      const double closing = -dr * (r0 > 0.0 ? 1.0 : -1.0); // rate of decrease of |r|
      if (closing <= 0.0)
        return t_max;
      return std::min(t_max, (1.0 - s) * d0 / closing);
    }
  } // namespace

  template <int dim>
  double additive_ccd(const ContactKind kind, const StencilVector<dim> &x0,
                      const StencilVector<dim> &x1, const double s, const double t_max,
                      const long max_iterations)
  {
    if constexpr (dim == 1)
      {
        (void)kind, (void)max_iterations;
        return vertex_vertex_ccd_1d(x0[0] - x0[1], (x1[0] - x0[0]) - (x1[1] - x0[1]), s, t_max);
      }
    else
      {
        const int n = n_stencil_vertices(kind);
        // Side A: the point (or edge a); side B: the rest.
        const int n_a = kind == ContactKind::edge_edge ? 2 : 1;

        StencilVector<dim>            p = x1 - x0;
        Eigen::Matrix<double, dim, 1> mean = Eigen::Matrix<double, dim, 1>::Zero();
        for (int i = 0; i < n; ++i)
          mean += p.template segment<dim>(i * dim);
        mean /= n;
        double max_a = 0.0, max_b = 0.0;
        for (int i = 0; i < n; ++i)
          {
            p.template segment<dim>(i * dim) -= mean;
            double &side_max = i < n_a ? max_a : max_b;
            side_max = std::max(side_max, p.template segment<dim>(i * dim).norm());
          }
        const double lp = max_a + max_b; // bound on |d d / dt| (unsquared distance)

        double d = std::sqrt(distance_sqr<dim>(kind, x0));
        if (!(d > 0.0))
          return 0.0;
        if (lp <= 0.0)
          return t_max;
        const double g = s * d; // guaranteed separation at accepted times
        double       t = 0.0;
        for (long it = 0; it < max_iterations; ++it)
          {
            // The distance cannot drop below g before t + (d - g) / lp.
            if (t + (d - g) / lp >= t_max)
              return t_max;
            const double t_next = t + (it == 0 ? d - g : d - 0.5 * g) / lp;
            // x0 + t p differs from the true position at t by a common translation only.
            const double d_next = std::sqrt(distance_sqr<dim>(kind, x0 + t_next * p));
            // Later steps only guarantee g/2: stop before entering (0, g).
            if (it > 0 && d_next < g)
              return t;
            t = t_next;
            d = d_next;
          }
        return t;
      }
  }

  template <int dim>
  double max_step(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V0,
                  const Eigen::MatrixXd &V1, const double min_separation_fraction,
                  const double inflation)
  {
    return max_step<dim>(surface, V0, V1, find_candidates<dim>(surface, V0, V1, inflation), min_separation_fraction);
  }

  template <int dim>
  double max_step(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V0,
                  const Eigen::MatrixXd &V1, const std::vector<Candidate> &candidates,
                  const double min_separation_fraction)
  {
    if (!(min_separation_fraction > 0.0 && min_separation_fraction < 1.0))
      throw std::invalid_argument("max_step: min_separation_fraction must be in (0, 1)");
    // Each pair is solved with t_max = 1 (not the running minimum) so that the result does
    // not depend on thread scheduling.
    return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, candidates.size(), 64), 1.0,
      [&](const auto &range, double t) {
        std::array<int, 4> v;
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          {
            const int          n  = stencil_vertices<dim>(surface, candidates[i], v);
            StencilVector<dim> x0 = StencilVector<dim>::Zero(), x1 = StencilVector<dim>::Zero();
            for (int a = 0; a < n; ++a)
              {
                x0.template segment<dim>(a * dim) = V0.row(v[a]).transpose();
                x1.template segment<dim>(a * dim) = V1.row(v[a]).transpose();
              }
            t = std::min(t, additive_ccd<dim>(candidates[i].kind, x0, x1, min_separation_fraction));
          }
        return t;
      },
      [](const double a, const double b) { return std::min(a, b); });
  }

#define RITR_INSTANTIATE(dim)                                                                    \
  template double additive_ccd<dim>(ContactKind, const StencilVector<dim> &,                  \
                                    const StencilVector<dim> &, double, double, long);        \
  template double max_step<dim>(const CollisionSurface<dim> &, const Eigen::MatrixXd &,       \
                                const Eigen::MatrixXd &, double, double);                     \
  template double max_step<dim>(const CollisionSurface<dim> &, const Eigen::MatrixXd &,       \
                                const Eigen::MatrixXd &, const std::vector<Candidate> &, double);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
