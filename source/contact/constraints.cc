#include <ritr/common/first_order_dual.h>
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
#include <type_traits>

namespace ritr::contact
{
  // Named (not anonymous) so that lambdas in the exported templates may capture these types.
  namespace constraints_detail
  {
    // Gradients alone at O(N) per operation (the second-order type costs O(N^2)), where no
    // Hessian is needed.
    using ritr::FirstOrderDual;
    using ritr::value_of;

    // f(a) for a plain double (value only) or a dual number (chain rule).
    inline double compose(const double, const double f, const double, const double)
    {
      return f;
    }
    template <int N>
    FirstOrderDual<N> compose(const FirstOrderDual<N> &a, const double f, const double df,
                              const double)
    {
      return chain(a, f, df);
    }
    template <int N>
    SecondOrderDual<N> compose(const SecondOrderDual<N> &a, const double f, const double df,
                               const double d2f)
    {
      return chain(a, f, df, d2f);
    }

    // Independent variable i with value v (a constant for plain doubles).
    template <typename S>
    S make_variable(const int i, const double v)
    {
      if constexpr (std::is_same_v<S, double>)
        return (void)i, v;
      else
        return S::variable(i, v);
    }

    // The vertices a constraint's barrier depends on at the current positions: only the
    // slots of its classified distance type, unless the edge-edge mollifier is active
    // (then all four). Derivatives are taken on this reduced stencil, which shrinks the
    // dual numbers, the PSD projections and the number of Hessian entries.
    struct LocalView
    {
      int                n = 0; // 0: inactive (d >= dhat^2)
      std::array<int, 4> slots{{0, 1, 2, 3}};
      DistanceClass      cls; // relative to the reduced stencil
      bool               mollified = false;
      double             distance_sqr = 0.0;
    };

    template <int dim>
    LocalView local_view(const Constraint &c, const StencilVector<dim> &x, const double dhat_sqr)
    {
      LocalView           v;
      const DistanceClass cls = classify<dim>(c.kind, x);
      v.distance_sqr = typed_distance_sqr<dim, double>(cls, to_kernel_points<dim>(x));
      if (!(v.distance_sqr < dhat_sqr))
        return v;
      if constexpr (dim == 3)
        if (c.kind == ContactKind::edge_edge)
          {
            const Eigen::Vector3d ea = x.template segment<3>(3) - x.template segment<3>(0);
            const Eigen::Vector3d eb = x.template segment<3>(9) - x.template segment<3>(6);
            if (ea.cross(eb).squaredNorm() < c.mollifier_threshold)
              {
                v.n         = 4;
                v.cls       = cls;
                v.mollified = true;
                return v;
              }
          }
      v.n         = n_slots(cls.type);
      v.cls.type  = cls.type;
      v.cls.slots = {{0, 1, 2, 3}}; // the reduced stencil is ordered like the slots
      for (int j = 0; j < v.n; ++j)
        v.slots[j] = cls.slots[j];
      return v;
    }

    // Unweighted m b(d) on the reduced stencil of v, with scalar type S.
    template <int dim, typename S>
    S local_barrier(const Constraint &c, const StencilVector<dim> &x, const LocalView &v,
                    const double dhat_sqr)
    {
      KernelStencil<S, dim> p{};
      for (int j = 0; j < v.n; ++j)
        for (int k = 0; k < dim; ++k)
          p[j][k] = make_variable<S>(j * dim + k, x[v.slots[j] * dim + k]);
      const S      d  = typed_distance_sqr<dim, S>(v.cls, p);
      const double dv = value_of(d);
      S b = compose(d, log_barrier(dv, dhat_sqr), log_barrier_derivative(dv, dhat_sqr),
                    log_barrier_second_derivative(dv, dhat_sqr));
      if constexpr (dim == 3)
        if (v.mollified)
          {
            const auto   n   = kernels::cross<S>(kernels::sub<S, 3>(p[1], p[0]),
                                              kernels::sub<S, 3>(p[3], p[2]));
            const S      cc  = kernels::dot<S, 3>(n, n);
            const double cv  = value_of(cc), eps = c.mollifier_threshold;
            b = b * compose(cc, edge_edge_mollifier(cv, eps),
                            edge_edge_mollifier_first_derivative(cv, eps),
                            edge_edge_mollifier_second_derivative(cv, eps));
          }
      (void)c;
      return b;
    }

    template <int dim>
    double local_barrier_value(const Constraint &c, const Eigen::MatrixXd &V, const double dhat_sqr)
    {
      const StencilVector<dim> x = gather_stencil<dim>(c, V);
      const LocalView          v = local_view<dim>(c, x, dhat_sqr);
      if (v.n == 0)
        return 0.0;
      if (v.distance_sqr <= 0.0)
        return std::numeric_limits<double>::infinity();
      return local_barrier<dim, double>(c, x, v, dhat_sqr);
    }

    // Calls f(dual) with the barrier of the reduced stencil evaluated in Dual<v.n * dim>.
    template <int dim, template <int> class Dual, typename F>
    void with_local_dual(const Constraint &c, const StencilVector<dim> &x, const LocalView &v,
                         const double dhat_sqr, F &&f)
    {
      switch (v.n)
        {
          case 2:
            f(local_barrier<dim, Dual<2 * dim>>(c, x, v, dhat_sqr));
            break;
          case 3:
            if constexpr (dim >= 2)
              f(local_barrier<dim, Dual<3 * dim>>(c, x, v, dhat_sqr));
            break;
          case 4:
            if constexpr (dim == 3)
              f(local_barrier<dim, Dual<4 * dim>>(c, x, v, dhat_sqr));
            break;
          default:
            break;
        }
    }

    // The unweighted barrier of c at V with its gradient on the full stencil: scale times the
    // gradient goes to out (stencil-ordered, zero where the barrier does not depend), the
    // value is returned (0 if inactive).
    template <int dim, typename Out>
    double local_gradient(const Constraint &c, const Eigen::MatrixXd &V, const double dhat_sqr,
                          const double scale, Out &&out)
    {
      const StencilVector<dim> x     = gather_stencil<dim>(c, V);
      const LocalView          v     = local_view<dim>(c, x, dhat_sqr);
      double                   value = 0.0;
      out.setZero();
      with_local_dual<dim, FirstOrderDual>(c, x, v, dhat_sqr, [&](const auto &b) {
        value = b.value;
        for (int j = 0; j < v.n; ++j)
          out.template segment<dim>(v.slots[j] * dim) =
            scale * b.grad.template segment<dim>(j * dim);
      });
      return value;
    }

    constexpr std::size_t grain = 64;
  } // namespace constraints_detail
  using namespace constraints_detail;

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
                            const StencilVector<dim> x = gather_stencil<dim>(c, V);
                            c.distance_type            = classify<dim>(c.kind, x).type;
                            c.distance_sqr             = distance_sqr<dim>(c.kind, x);
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
    // Deterministic reduction: line searches compare energies, which must not depend on
    // thread scheduling.
    return tbb::parallel_deterministic_reduce(
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
    constexpr int N        = stencil_dofs<dim>;
    const double  dhat_sqr = dhat * dhat;
    // Local gradients (on the full stencil) in parallel, then a serial scatter: no write
    // conflicts, no locks, deterministic sums.
    Eigen::MatrixXd local(N, constraints.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, constraints.size(), grain),
                      [&](const auto &range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          local_gradient<dim>(constraints[i], V, dhat_sqr,
                                              weights.weight(constraints[i]), local.col(i));
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

  namespace
  {
    // The local Hessians of the constraints into `exact` and/or `projected` (null: not
    // wanted), each constraint's entries in the same range of both lists.
    template <int dim>
    void barrier_hessians(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V, const double dhat,
                          const ConstraintWeights &weights, Triplets *exact, Triplets *projected)
    {
      const double      dhat_sqr = dhat * dhat;
      const std::size_t n_c      = constraints.size();
      // Pass 1: which vertices each constraint involves, hence its number of entries.
      std::vector<LocalView>   views(n_c);
      std::vector<std::size_t> offset(n_c + 1, 0);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_c, grain), [&](const auto &range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          views[i] = local_view<dim>(constraints[i], gather_stencil<dim>(constraints[i], V), dhat_sqr);
      });
      for (std::size_t i = 0; i < n_c; ++i)
        offset[i + 1] = offset[i] + static_cast<std::size_t>(views[i].n * dim * views[i].n * dim);

      // Pass 2: local Hessians written to disjoint ranges.
      for (Triplets *t : {exact, projected})
        if (t)
          t->resize(offset.back());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_c, grain), [&](const auto &range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          {
            const Constraint        &c = constraints[i];
            const LocalView         &v = views[i];
            const StencilVector<dim> x = gather_stencil<dim>(c, V);
            const double             w = weights.weight(c);
            with_local_dual<dim, SecondOrderDual>(c, x, v, dhat_sqr, [&](const auto &b) {
              using Matrix     = std::decay_t<decltype(b.hess)>;
              const Matrix H   = w * b.hess;
              const auto write = [&](const Matrix &m, Triplets &out) {
                auto     *entry = &out[offset[i]];
                const int n     = static_cast<int>(m.rows());
                for (int r = 0; r < n; ++r)
                  for (int q = 0; q < n; ++q)
                    *entry++ = Eigen::Triplet<double>(c.vertices[v.slots[r / dim]] * dim + r % dim,
                                                      c.vertices[v.slots[q / dim]] * dim + q % dim, m(r, q));
              };
              if (exact)
                write(H, *exact);
              if (projected)
                write(project_to_psd(H), *projected);
            });
          }
      });
    }
  } // namespace

  template <int dim>
  Triplets
  barrier_hessian(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                  const double dhat, const ConstraintWeights &weights, const bool project_psd)
  {
    Triplets triplets;
    barrier_hessians<dim>(constraints, V, dhat, weights, project_psd ? nullptr : &triplets,
                          project_psd ? &triplets : nullptr);
    return triplets;
  }

  template <int dim>
  std::pair<Triplets, Triplets>
  barrier_hessian_and_projection(const std::vector<Constraint> &constraints, const Eigen::MatrixXd &V,
                                 const double dhat, const ConstraintWeights &weights)
  {
    std::pair<Triplets, Triplets> hessians;
    barrier_hessians<dim>(constraints, V, dhat, weights, &hessians.first, &hessians.second);
    return hessians;
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
                            const Constraint &c = constraints[i];
                            BarrierTerm      &t = terms[i];
                            t.gradient.resize(c.n_vertices * dim);
                            t.value = local_gradient<dim>(c, V, dhat_sqr, 1.0, t.gradient);
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
  template Triplets barrier_hessian<dim>(                           \
    const std::vector<Constraint> &, const Eigen::MatrixXd &, double,                          \
    const ConstraintWeights &, bool);                                                          \
  template std::pair<Triplets, Triplets> barrier_hessian_and_projection<dim>(                  \
    const std::vector<Constraint> &, const Eigen::MatrixXd &, double, const ConstraintWeights &); \
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
