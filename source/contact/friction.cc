#include <ritr/common/psd_projection.h>
#include <ritr/contact/barrier.h>
#include <ritr/contact/friction.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ritr::contact
{
  double friction_f0(const double y, const double eps)
  {
    if (y >= eps)
      return y;
    return -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
  }

  double friction_f1(const double y, const double eps)
  {
    if (y >= eps)
      return 1.0;
    return -y * y / (eps * eps) + 2.0 * y / eps;
  }

  double friction_f1_over_y(const double y, const double eps)
  {
    if (y >= eps)
      return 1.0 / y;
    return -y / (eps * eps) + 2.0 / eps;
  }

  double friction_f2_term(const double y, const double eps)
  {
    if (y <= 0.0)
      return 0.0; // multiplies u u^T = 0
    if (y >= eps)
      return -1.0 / (y * y * y);
    return -1.0 / (eps * eps * y);
  }

  namespace
  {
    template <int dim>
    using Vec = Eigen::Matrix<double, dim, 1>;
    template <int dim>
    using Basis = Eigen::Matrix<double, dim, (dim > 1 ? dim - 1 : 1)>;

    // Unit vector orthogonal to unit n (3D).
    Eigen::Vector3d any_orthogonal(const Eigen::Vector3d &n)
    {
      int axis;
      n.cwiseAbs().minCoeff(&axis);
      return n.cross(Eigen::Vector3d::Unit(axis)).normalized();
    }

    // Basis of the plane orthogonal to the unit normal n (3D).
    Basis<3> basis_from_normal(const Eigen::Vector3d &n)
    {
      Basis<3> T;
      T.col(0) = any_orthogonal(n);
      T.col(1) = n.cross(T.col(0));
      return T;
    }

    // Basis whose first column is the unit direction t0 and second column is orthogonal to
    // t0 and to `normal_hint` when that is usable (3D).
    Basis<3> basis_from_direction(const Eigen::Vector3d &t0, const Eigen::Vector3d &normal_hint)
    {
      Basis<3>              T;
      T.col(0)              = t0;
      const Eigen::Vector3d c = t0.cross(normal_hint);
      const double          cn = c.norm();
      T.col(1) = cn > 1e-12 * normal_hint.norm() && cn > 0.0 ? Eigen::Vector3d(c / cn)
                                                                : any_orthogonal(t0);
      return T;
    }

    template <int dim>
    bool make_friction_constraint(const Constraint &c, const Eigen::MatrixXd &V_lag,
                                  const double dhat_sqr, const double kappa,
                                  const ConstraintWeights &weights, const double mu,
                                  FrictionConstraint<dim> &fc)
    {
      const StencilVector<dim> xs  = gather_stencil<dim>(c, V_lag);
      const DistanceClass      cls = classify<dim>(c.kind, xs);
      const double d = typed_distance_sqr<dim, double>(cls, to_kernel_points<dim>(xs));
      if (!(d > 0.0) || d >= dhat_sqr)
        return false;
      const auto x = [&](const int i) -> Vec<dim> { return xs.template segment<dim>(i * dim); };

      double m = 1.0;
      if constexpr (dim == 3)
        if (c.kind == ContactKind::edge_edge)
          m = edge_edge_mollifier((x(1) - x(0)).cross(x(3) - x(2)).squaredNorm(),
                                  c.mollifier_threshold);
      // -db/d(sqrt d) = -b'(d) 2 sqrt(d) > 0 inside the barrier's range.
      const double lambda =
        -kappa * weights.weight(c) * m * log_barrier_derivative(d, dhat_sqr) * 2.0 * std::sqrt(d);
      if (!(lambda > 0.0))
        return false;

      std::array<double, 4> coef = {{0.0, 0.0, 0.0, 0.0}};
      const auto           &s    = cls.slots;
      const Eigen::Vector2d prm  = closest_point_parameters<dim>(cls, xs);
      Basis<dim>            T    = Basis<dim>::Zero();
      switch (cls.type)
        {
          case DistanceType::point_point:
            {
              coef[s[0]] = 1.0, coef[s[1]] = -1.0;
              const Vec<dim> n = (x(s[0]) - x(s[1])).normalized();
              if constexpr (dim == 2)
                T << -n[1], n[0];
              else if constexpr (dim == 3)
                T = basis_from_normal(n);
              break;
            }
          case DistanceType::point_line:
            {
              const double a = std::clamp(prm[0], 0.0, 1.0);
              coef[s[0]] = 1.0, coef[s[1]] = -(1.0 - a), coef[s[2]] = -a;
              const Vec<dim> t0 = (x(s[2]) - x(s[1])).normalized();
              if constexpr (dim == 2)
                T = t0;
              else if constexpr (dim == 3)
                T = basis_from_direction(t0, x(s[0]) - x(s[1]));
              break;
            }
          case DistanceType::point_plane:
            if constexpr (dim == 3)
              {
                coef[s[0]] = 1.0, coef[s[1]] = -(1.0 - prm[0] - prm[1]);
                coef[s[2]] = -prm[0], coef[s[3]] = -prm[1];
                const Vec<3> e1 = x(s[2]) - x(s[1]);
                const Vec<3> n  = e1.cross(x(s[3]) - x(s[1])).normalized();
                T.col(0)        = e1.normalized();
                T.col(1)        = n.cross(T.col(0));
              }
            break;
          case DistanceType::line_line:
            if constexpr (dim == 3)
              {
                coef[s[0]] = 1.0 - prm[0], coef[s[1]] = prm[0];
                coef[s[2]] = -(1.0 - prm[1]), coef[s[3]] = -prm[1];
                const Vec<3> ea = x(s[1]) - x(s[0]);
                const Vec<3> n  = ea.cross(x(s[3]) - x(s[2])).normalized();
                T.col(0)        = ea.normalized();
                T.col(1)        = n.cross(T.col(0));
              }
            break;
        }

      fc.n_vertices = 0;
      for (int i = 0; i < c.n_vertices; ++i)
        if (coef[i] != 0.0)
          {
            fc.vertices[fc.n_vertices]     = c.vertices[i];
            fc.coefficients[fc.n_vertices] = coef[i];
            ++fc.n_vertices;
          }
      fc.basis        = T;
      fc.normal_force = lambda;
      fc.mu           = mu;
      return true;
    }

    // Tangential displacement u = T^T sum_i c_i (x_i - x_i^start).
    template <int dim>
    Eigen::Matrix<double, dim - 1, 1> tangential_displacement(const FrictionConstraint<dim> &fc,
                                                              const Eigen::MatrixXd &V,
                                                              const Eigen::MatrixXd &V_start)
    {
      Vec<dim> r = Vec<dim>::Zero();
      for (int i = 0; i < fc.n_vertices; ++i)
        r += fc.coefficients[i] * (V.row(fc.vertices[i]) - V_start.row(fc.vertices[i])).transpose();
      return fc.basis.transpose() * r;
    }

    void check_eps(const double eps)
    {
      if (!(eps > 0.0))
        throw std::invalid_argument("friction: epsilon_v_times_h must be positive");
    }
  } // namespace

  template <int dim>
  std::vector<FrictionConstraint<dim>>
  build_friction_constraints(const std::vector<Constraint> &constraints,
                             const Eigen::MatrixXd &V_lag, const double dhat, const double kappa,
                             const ConstraintWeights &weights, const double mu)
  {
    if constexpr (dim == 1)
      {
        (void)constraints, (void)V_lag, (void)dhat, (void)kappa, (void)weights, (void)mu;
        return {}; // no tangent space in 1D
      }
    else
      {
        const double                         dhat_sqr = dhat * dhat;
        std::vector<FrictionConstraint<dim>> all(constraints.size());
        std::vector<char>                    keep(constraints.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, constraints.size(), 64),
                          [&](const auto &range) {
                            for (std::size_t i = range.begin(); i != range.end(); ++i)
                              keep[i] = make_friction_constraint<dim>(constraints[i], V_lag,
                                                                      dhat_sqr, kappa, weights,
                                                                      mu, all[i]);
                          });
        std::vector<FrictionConstraint<dim>> result;
        result.reserve(std::count(keep.begin(), keep.end(), 1));
        for (std::size_t i = 0; i < all.size(); ++i)
          if (keep[i])
            result.push_back(all[i]);
        return result;
      }
  }

  template <int dim>
  double friction_energy(const std::vector<FrictionConstraint<dim>> &friction,
                         const Eigen::MatrixXd &V, const Eigen::MatrixXd &V_start,
                         const double eps)
  {
    if constexpr (dim == 1)
      {
        (void)friction, (void)V, (void)V_start, (void)eps;
        return 0.0;
      }
    else
      {
        check_eps(eps);
        // Deterministic reduction: line searches compare energies, which must not depend on
        // thread scheduling.
        return tbb::parallel_deterministic_reduce(
          tbb::blocked_range<std::size_t>(0, friction.size(), 256), 0.0,
          [&](const auto &range, double sum) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
              {
                const auto &fc = friction[i];
                sum += fc.mu * fc.normal_force *
                       friction_f0(tangential_displacement<dim>(fc, V, V_start).norm(), eps);
              }
            return sum;
          },
          std::plus<double>());
      }
  }

  template <int dim>
  Eigen::VectorXd friction_gradient(const std::vector<FrictionConstraint<dim>> &friction,
                                    const Eigen::MatrixXd &V, const Eigen::MatrixXd &V_start,
                                    const double eps)
  {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(V.rows() * dim);
    if constexpr (dim == 1)
      {
        (void)friction, (void)V_start, (void)eps;
        return g;
      }
    else
      {
        check_eps(eps);
        // Per constraint: the common vector mu lambda f1/y T u; vertex i gets c_i times it.
        Eigen::Matrix<double, dim, Eigen::Dynamic> local(dim, friction.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, friction.size(), 256),
                          [&](const auto &range) {
                            for (std::size_t i = range.begin(); i != range.end(); ++i)
                              {
                                const auto  &fc = friction[i];
                                const auto   u  = tangential_displacement<dim>(fc, V, V_start);
                                local.col(i) = fc.mu * fc.normal_force *
                                               friction_f1_over_y(u.norm(), eps) * (fc.basis * u);
                              }
                          });
        for (std::size_t i = 0; i < friction.size(); ++i)
          for (int a = 0; a < friction[i].n_vertices; ++a)
            g.template segment<dim>(friction[i].vertices[a] * dim) +=
              friction[i].coefficients[a] * local.col(i);
        return g;
      }
  }

  namespace
  {
    // The constraints' Hessians into `exact` and/or `projected` (null: not wanted), each
    // constraint's entries in the same range of both lists.
    template <int dim>
    void friction_hessians(const std::vector<FrictionConstraint<dim>> &friction, const Eigen::MatrixXd &V,
                           const Eigen::MatrixXd &V_start, const double eps, Triplets *exact, Triplets *projected)
    {
      if constexpr (dim == 1)
        (void)friction, (void)V, (void)V_start, (void)eps, (void)exact, (void)projected;
      else
        {
          check_eps(eps);
          std::vector<std::size_t> offset(friction.size() + 1, 0);
          for (std::size_t i = 0; i < friction.size(); ++i)
            offset[i + 1] =
              offset[i] + static_cast<std::size_t>(friction[i].n_vertices * friction[i].n_vertices * dim * dim);
          for (Triplets *t : {exact, projected})
            if (t)
              t->resize(offset.back());
          tbb::parallel_for(tbb::blocked_range<std::size_t>(0, friction.size(), 256), [&](const auto &range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
              {
                const auto  &fc = friction[i];
                const auto   u  = tangential_displacement<dim>(fc, V, V_start);
                const double y  = u.norm();
                using Tangential = Eigen::Matrix<double, dim - 1, dim - 1>;
                const Tangential M = friction_f1_over_y(y, eps) * Tangential::Identity() +
                                     friction_f2_term(y, eps) * u * u.transpose();
                const auto write = [&](const Tangential &m, Triplets &out) {
                  const Eigen::Matrix<double, dim, dim> A = fc.mu * fc.normal_force * fc.basis * m * fc.basis.transpose();
                  auto *entry = &out[offset[i]];
                  for (int a = 0; a < fc.n_vertices; ++a)
                    for (int b = 0; b < fc.n_vertices; ++b)
                      {
                        const double cab = fc.coefficients[a] * fc.coefficients[b];
                        for (int k = 0; k < dim; ++k)
                          for (int l = 0; l < dim; ++l)
                            *entry++ = Eigen::Triplet<double>(fc.vertices[a] * dim + k, fc.vertices[b] * dim + l,
                                                              cab * A(k, l));
                      }
                };
                if (exact)
                  write(M, *exact);
                if (projected)
                  write(project_to_psd(M), *projected);
              }
          });
        }
    }
  } // namespace

  template <int dim>
  Triplets
  friction_hessian(const std::vector<FrictionConstraint<dim>> &friction, const Eigen::MatrixXd &V,
                   const Eigen::MatrixXd &V_start, const double eps, const bool project_psd)
  {
    Triplets triplets;
    friction_hessians<dim>(friction, V, V_start, eps, project_psd ? nullptr : &triplets,
                           project_psd ? &triplets : nullptr);
    return triplets;
  }

  template <int dim>
  std::pair<Triplets, Triplets>
  friction_hessian_and_projection(const std::vector<FrictionConstraint<dim>> &friction, const Eigen::MatrixXd &V,
                                  const Eigen::MatrixXd &V_start, const double eps)
  {
    std::pair<Triplets, Triplets> hessians;
    friction_hessians<dim>(friction, V, V_start, eps, &hessians.first, &hessians.second);
    return hessians;
  }

#define RITR_INSTANTIATE(dim)                                                                    \
  template std::vector<FrictionConstraint<dim>> build_friction_constraints<dim>(               \
    const std::vector<Constraint> &, const Eigen::MatrixXd &, double, double,                  \
    const ConstraintWeights &, double);                                                        \
  template double friction_energy<dim>(const std::vector<FrictionConstraint<dim>> &,           \
                                       const Eigen::MatrixXd &, const Eigen::MatrixXd &,       \
                                       double);                                                \
  template Eigen::VectorXd friction_gradient<dim>(const std::vector<FrictionConstraint<dim>> &,\
                                                  const Eigen::MatrixXd &,                     \
                                                  const Eigen::MatrixXd &, double);            \
  template Triplets friction_hessian<dim>(                          \
    const std::vector<FrictionConstraint<dim>> &, const Eigen::MatrixXd &,                     \
    const Eigen::MatrixXd &, double, bool);                                                    \
  template std::pair<Triplets, Triplets> friction_hessian_and_projection<dim>(                 \
    const std::vector<FrictionConstraint<dim>> &, const Eigen::MatrixXd &, const Eigen::MatrixXd &, double);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
