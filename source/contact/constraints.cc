#include <ritr/common/psd_projection.h>
#include <ritr/contact/barrier.h>
#include <ritr/contact/constraints.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ritr::contact
{
  namespace
  {
    // f(a) for a plain double (value only) or a dual number (chain rule).
    inline double compose(const double, const double f, const double, const double)
    {
      return f;
    }
    template <int N>
    SecondOrderDual<N> compose(const SecondOrderDual<N> &a, const double f, const double df,
                               const double d2f)
    {
      return chain(a, f, df, d2f);
    }

    // Unweighted m b(d) on stencil points x (classified from their values).
    template <int dim, typename S>
    S local_barrier(const Constraint &c, const KernelStencil<S, dim> &x, const DistanceClass &cls,
                    const double dhat_sqr)
    {
      const S      d  = typed_distance_sqr<dim, S>(cls, x);
      const double dv = value_of(d);
      if (dv >= dhat_sqr)
        return S(0.0);
      S b = compose(d, barrier(dv, dhat_sqr), barrier_first_derivative(dv, dhat_sqr),
                    barrier_second_derivative(dv, dhat_sqr));
      if constexpr (dim == 3)
        if (c.kind == ContactKind::edge_edge)
          {
            const auto ea = kernels::sub<S, 3>(x[1], x[0]);
            const auto eb = kernels::sub<S, 3>(x[3], x[2]);
            const auto n  = kernels::cross<S>(ea, eb);
            const S    cc = kernels::dot<S, 3>(n, n);
            const double cv = value_of(cc), eps = c.mollifier_threshold;
            if (cv < eps)
              b = b * compose(cc, edge_edge_mollifier(cv, eps),
                              edge_edge_mollifier_first_derivative(cv, eps),
                              edge_edge_mollifier_second_derivative(cv, eps));
          }
      return b;
    }

    template <int dim>
    double local_barrier_value(const Constraint &c, const Eigen::MatrixXd &V, const double dhat_sqr)
    {
      const StencilVector<dim> x   = gather_stencil<dim>(c, V);
      const DistanceClass      cls = classify<dim>(c.kind, x);
      const auto               p   = to_kernel_points<dim>(x);
      if (typed_distance_sqr<dim, double>(cls, p) <= 0.0)
        return std::numeric_limits<double>::infinity();
      return local_barrier<dim, double>(c, p, cls, dhat_sqr);
    }

    template <int dim>
    SecondOrderDual<stencil_dofs<dim>> local_barrier_dual(const Constraint &c,
                                                          const Eigen::MatrixXd &V,
                                                          const double dhat_sqr)
    {
      using Dual                 = SecondOrderDual<stencil_dofs<dim>>;
      const StencilVector<dim> x = gather_stencil<dim>(c, V);
      const DistanceClass cls    = classify<dim>(c.kind, x);
      // Cheap value test first: inactive constraints need no derivatives.
      if (typed_distance_sqr<dim, double>(cls, to_kernel_points<dim>(x)) >= dhat_sqr)
        return Dual(0.0);
      return local_barrier<dim, Dual>(c, to_dual_points<dim>(x), cls, dhat_sqr);
    }

    constexpr std::size_t grain = 64;
  } // namespace

  template <int dim>
  StencilVector<dim> gather_stencil(const Constraint &c, const Eigen::MatrixXd &V)
  {
    StencilVector<dim> x = StencilVector<dim>::Zero();
    for (int i = 0; i < c.n_vertices; ++i)
      for (int k = 0; k < dim; ++k)
        x[i * dim + k] = V(c.vertices[i], k);
    return x;
  }

  template <int dim>
  double constraint_distance_sqr(const Constraint &c, const Eigen::MatrixXd &V)
  {
    return distance_sqr<dim>(c.kind, gather_stencil<dim>(c, V));
  }

  template <int dim>
  std::vector<Constraint> build_constraints(const CollisionSurface<dim>  &surface,
                                            const std::vector<Candidate> &candidates,
                                            const Eigen::MatrixXd &V, const Eigen::MatrixXd &rest_V,
                                            const double dhat)
  {
    if (V.rows() != surface.n_vertices || V.cols() != dim || rest_V.rows() != V.rows() ||
        rest_V.cols() != dim)
      throw std::invalid_argument("build_constraints: position matrix has the wrong shape");
    const double            dhat_sqr = dhat * dhat;
    std::vector<Constraint> all(candidates.size());
    std::vector<char>       active(candidates.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), grain),
                      [&](const auto &range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          {
                            const Candidate &cand = candidates[i];
                            Constraint      &c    = all[i];
                            c.kind                = cand.kind;
                            c.first               = cand.first;
                            c.second              = cand.second;
                            c.n_vertices = stencil_vertices<dim>(surface, cand, c.vertices);
                            const StencilVector<dim> x   = gather_stencil<dim>(c, V);
                            const DistanceClass      cls = classify<dim>(c.kind, x);
                            c.distance_type              = cls.type;
                            c.distance_sqr = typed_distance_sqr<dim, double>(cls, to_kernel_points<dim>(x));
                            if (!(c.distance_sqr < dhat_sqr))
                              continue;
                            active[i] = 1;
                            if (c.kind == ContactKind::edge_edge)
                              {
                                c.weight_owner = WeightOwner::edge;
                                c.weight_index = c.first;
                                if constexpr (dim == 3)
                                  c.mollifier_threshold = edge_edge_mollifier_threshold(
                                    rest_V.row(c.vertices[0]).transpose(),
                                    rest_V.row(c.vertices[1]).transpose(),
                                    rest_V.row(c.vertices[2]).transpose(),
                                    rest_V.row(c.vertices[3]).transpose());
                              }
                            else
                              {
                                c.weight_owner = WeightOwner::vertex;
                                c.weight_index = c.vertices[0];
                              }
                          }
                      });
    std::vector<Constraint> result;
    result.reserve(std::count(active.begin(), active.end(), 1));
    for (std::size_t i = 0; i < all.size(); ++i)
      if (active[i])
        result.push_back(all[i]);
    return result;
  }

  template <int dim>
  std::vector<Constraint> build_constraints(const CollisionSurface<dim> &surface,
                                            const Eigen::MatrixXd &V, const Eigen::MatrixXd &rest_V,
                                            const double dhat)
  {
    return build_constraints<dim>(surface, find_candidates<dim>(surface, V, dhat), V, rest_V,
                                  dhat);
  }

  template <int dim>
  double barrier_energy(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                        const double dhat, const ConstraintWeights &weights)
  {
    const double dhat_sqr = dhat * dhat;
    return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, constraints.size(), grain), 0.0,
      [&](const auto &range, double sum) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          {
            const double b = local_barrier_value<dim>(constraints[i], V, dhat_sqr);
            if (b != 0.0)
              sum += weights.weight(constraints[i]) * b;
          }
        return sum;
      },
      std::plus<double>());
  }

  template <int dim>
  Eigen::VectorXd barrier_gradient(const std::vector<Constraint> &constraints,
                                   const Eigen::MatrixXd &V, const double dhat,
                                   const ConstraintWeights &weights)
  {
    constexpr int   N        = stencil_dofs<dim>;
    const double    dhat_sqr = dhat * dhat;
    // Local gradients in parallel, then a serial scatter (no write conflicts, no locks).
    Eigen::MatrixXd local(N, constraints.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, constraints.size(), grain),
                      [&](const auto &range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          local.col(i) = weights.weight(constraints[i]) *
                                         local_barrier_dual<dim>(constraints[i], V, dhat_sqr).grad;
                      });
    Eigen::VectorXd g = Eigen::VectorXd::Zero(V.rows() * dim);
    for (std::size_t i = 0; i < constraints.size(); ++i)
      {
        const Constraint &c = constraints[i];
        for (int a = 0; a < c.n_vertices; ++a)
          g.template segment<dim>(c.vertices[a] * dim) += local.col(i).template segment<dim>(a * dim);
      }
    return g;
  }

  template <int dim>
  std::vector<Eigen::Triplet<double>>
  barrier_hessian(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                  const double dhat, const ConstraintWeights &weights, const bool project_psd)
  {
    constexpr int                       N        = stencil_dofs<dim>;
    const double                        dhat_sqr = dhat * dhat;
    std::vector<Eigen::Triplet<double>> triplets(constraints.size() * N * N);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, constraints.size(), grain),
                      [&](const auto &range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          {
                            const Constraint  &c = constraints[i];
                            StencilMatrix<dim> H =
                              weights.weight(c) * local_barrier_dual<dim>(c, V, dhat_sqr).hess;
                            if (project_psd && !H.isZero(0.0))
                              H = project_to_psd(H);
                            auto *out = &triplets[i * N * N];
                            for (int a = 0; a < N; ++a)
                              for (int b = 0; b < N; ++b)
                                *out++ = Eigen::Triplet<double>(
                                  c.vertices[a / dim] * dim + a % dim,
                                  c.vertices[b / dim] * dim + b % dim, H(a, b));
                          }
                      });
    return triplets;
  }

  template <int dim>
  std::vector<BarrierTerm> unweighted_barrier_terms(const std::vector<Constraint> &constraints,
                                                    const Eigen::MatrixXd &V, const double dhat)
  {
    const double             dhat_sqr = dhat * dhat;
    std::vector<BarrierTerm> terms(constraints.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, constraints.size(), grain),
                      [&](const auto &range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          {
                            const auto b = local_barrier_dual<dim>(constraints[i], V, dhat_sqr);
                            terms[i].value    = b.value;
                            terms[i].gradient = b.grad.head(constraints[i].n_vertices * dim);
                          }
                      });
    return terms;
  }

  template <int dim>
  double minimum_distance(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V)
  {
    const double d_sqr = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, constraints.size(), grain),
      std::numeric_limits<double>::infinity(),
      [&](const auto &range, double m) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          m = std::min(m, constraint_distance_sqr<dim>(constraints[i], V));
        return m;
      },
      [](const double a, const double b) { return std::min(a, b); });
    return std::sqrt(std::max(d_sqr, 0.0));
  }

  template <int dim>
  double minimum_distance(const CollisionSurface<dim> &surface, const Eigen::MatrixXd &V)
  {
    const double diagonal = bbox_diagonal(V);
    // Initial guess of the search radius: the typical primitive size.
    double radius = 0.0;
    if constexpr (dim > 1)
      {
        for (const auto &e : surface.edges)
          radius += (V.row(e[0]) - V.row(e[1])).norm();
        if (!surface.edges.empty())
          radius /= static_cast<double>(surface.edges.size());
      }
    else
      radius = surface.n_vertices > 1 ? diagonal / surface.n_vertices : 0.0;
    if (!(radius > 0.0))
      radius = diagonal > 0.0 ? diagonal : 1.0;

    // Every pair closer than `radius` is a candidate, so once a candidate closer than
    // `radius` is found it is the global minimum. A radius beyond the bounding box diagonal
    // makes every pair a candidate.
    while (true)
      {
        const auto   candidates = find_candidates<dim>(surface, V, radius);
        const double d_sqr      = tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, candidates.size(), grain),
          std::numeric_limits<double>::infinity(),
          [&](const auto &range, double m) {
            std::array<int, 4> v;
            for (std::size_t i = range.begin(); i != range.end(); ++i)
              {
                const int          n = stencil_vertices<dim>(surface, candidates[i], v);
                StencilVector<dim> x = StencilVector<dim>::Zero();
                for (int a = 0; a < n; ++a)
                  x.template segment<dim>(a * dim) = V.row(v[a]).transpose();
                m = std::min(m, distance_sqr<dim>(candidates[i].kind, x));
              }
            return m;
          },
          [](const double a, const double b) { return std::min(a, b); });
        const double d = std::sqrt(std::max(d_sqr, 0.0));
        if (d < radius || radius > diagonal)
          return d;
        radius *= 4.0;
      }
  }

#define RITR_INSTANTIATE(dim)                                                                    \
  template StencilVector<dim> gather_stencil<dim>(const Constraint &, const Eigen::MatrixXd &);\
  template double constraint_distance_sqr<dim>(const Constraint &, const Eigen::MatrixXd &);   \
  template std::vector<Constraint> build_constraints<dim>(                                     \
    const CollisionSurface<dim> &, const std::vector<Candidate> &, const Eigen::MatrixXd &,    \
    const Eigen::MatrixXd &, double);                                                          \
  template std::vector<Constraint> build_constraints<dim>(                                     \
    const CollisionSurface<dim> &, const Eigen::MatrixXd &, const Eigen::MatrixXd &, double);  \
  template double barrier_energy<dim>(const std::vector<Constraint> &, const Eigen::MatrixXd &,\
                                      double, const ConstraintWeights &);                      \
  template Eigen::VectorXd barrier_gradient<dim>(const std::vector<Constraint> &,              \
                                                 const Eigen::MatrixXd &, double,              \
                                                 const ConstraintWeights &);                   \
  template std::vector<Eigen::Triplet<double>> barrier_hessian<dim>(                           \
    const std::vector<Constraint> &, const Eigen::MatrixXd &, double,                          \
    const ConstraintWeights &, bool);                                                          \
  template std::vector<BarrierTerm> unweighted_barrier_terms<dim>(                             \
    const std::vector<Constraint> &, const Eigen::MatrixXd &, double);                         \
  template double minimum_distance<dim>(const std::vector<Constraint> &,                       \
                                        const Eigen::MatrixXd &);                              \
  template double minimum_distance<dim>(const CollisionSurface<dim> &, const Eigen::MatrixXd &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
