#include <ritr/adaptivity/line_search_outer.h>
#include <ritr/common/psd_projection.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace ritr
{
  namespace
  {
    Eigen::SparseMatrix<double> to_sparse(const Triplets &t, const Eigen::Index rows, const Eigen::Index cols)
    {
      Eigen::SparseMatrix<double> m(rows, cols);
      m.setFromTriplets(t.begin(), t.end());
      return m;
    }

    void append(const Eigen::SparseMatrix<double> &m, const Eigen::Index row0, const Eigen::Index col0,
                const bool transpose, Triplets &out)
    {
      for (int k = 0; k < m.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
          transpose ? out.emplace_back(col0 + it.col(), row0 + it.row(), it.value()) :
                      out.emplace_back(row0 + it.row(), col0 + it.col(), it.value());
    }
  } // namespace

  NewtonSettings outer_newton_settings(const double epsilon_r, const unsigned int max_iterations)
  {
    NewtonSettings s;
    s.tolerance                 = epsilon_r;
    s.max_iterations            = max_iterations;
    s.armijo                    = 0;  // any trial that does not raise R (Algorithm 1)
    s.projection                = HessianProjection::always;  // the objective picks its Hessian
    s.judge_by_gradient         = false;
    s.round_off_stall_converges = false;  // a search without decrease is reported as such
    return s;
  }

  template <int dim>
  NestedOuterObjective<dim>::NestedOuterObjective(const OuterSetting<dim> &setting, const RitrHessian hessian,
                                                  const double filter_threshold, const double trust,
                                                  const Eigen::VectorXd &u0, const Eigen::VectorXd &z0, const double r0)
    : setting_(setting)
    , hessian_kind_(hessian)
    , filter_threshold_(filter_threshold)
    , trust_(trust)
    , u0_(u0)
    , p_(Eigen::VectorXd::Zero(setting.basis.cols()))
    , z_(z0)
    , r_(r0)
  {}

  template <int dim>
  void NestedOuterObjective<dim>::begin_iteration(const Eigen::VectorXd &p)
  {
    const bool truncated = hessian_kind_ == RitrHessian::truncated;
    setting_.terms.set_reference(reference(p));
    derivatives_ = setting_.terms.reference_derivatives(z_, setting_.terms.candidates_at(z_),
                                                        truncated ? ReferenceBlock::following : ReferenceBlock::exact,
                                                        !truncated);
  }

  template <int dim>
  double NestedOuterObjective<dim>::value(const Eigen::VectorXd &p)
  {
    if (p == p_)
      return r_;
    // Every trial mesh re-solves the implicit step, warm-started from the current x; a mesh
    // where that fails is rejected like one that raises R.
    trial_p_ = p;
    trial_z_ = z_;
    trial_r_ = std::numeric_limits<double>::infinity();
    if (setting_.solve_on_mesh(reference(p), trial_z_))
      trial_r_ = setting_.terms.objective(trial_z_, setting_.terms.candidates_at(trial_z_));
    return trial_r_;
  }

  template <int dim>
  void NestedOuterObjective<dim>::accept(const Eigen::VectorXd &p)
  {
    (void)p;  // the last trial evaluated is the one taken
    p_ = trial_p_;
    z_ = trial_z_;
    r_ = trial_r_;
  }

  template <int dim>
  void NestedOuterObjective<dim>::gradient(const Eigen::VectorXd &, Eigen::VectorXd &g)
  {
    g = setting_.basis.transpose() * derivatives_.gu;
  }

  template <int dim>
  void NestedOuterObjective<dim>::hessian(const Eigen::VectorXd &, Triplets &h, bool)
  {
    const auto                       &d     = derivatives_;
    const Eigen::SparseMatrix<double> &basis = setting_.basis;
    const Eigen::Index                n_u   = basis.rows();
    const Eigen::SparseMatrix<double> huu   = to_sparse(d.huu, n_u, n_u);
    if (hessian_kind_ == RitrHessian::truncated)
      {
        append(basis.transpose() * huu * basis, 0, 0, false, h);
        return;
      }
    // Schur complement on the free state entries: S = H_uu - H_xu^T H_xx^{-1} H_xu.
    const auto           &free = setting_.free_state;
    const Eigen::Index    n_z = d.gx.size(), n_f = free.size();
    const Eigen::MatrixXd hxx = Eigen::MatrixXd(to_sparse(d.hxx, n_z, n_z));
    const Eigen::MatrixXd hxu = Eigen::MatrixXd(to_sparse(d.hxu, n_z, n_u));
    Eigen::MatrixXd       hxx_f(n_f, n_f), hxu_f(n_f, n_u);
    for (Eigen::Index a = 0; a < n_f; ++a)
      {
        hxu_f.row(a) = hxu.row(free[a]);
        for (Eigen::Index b = 0; b < n_f; ++b)
          hxx_f(a, b) = hxx(free[a], free[b]);
      }
    Eigen::MatrixXd response = hxx_f.ldlt().solve(hxu_f);  // -dx/du
    if (hessian_kind_ == RitrHessian::filtered)
      {
        const double threshold = filter_threshold_ * response.cwiseAbs().maxCoeff();
        response               = (response.array().abs() < threshold).select(0.0, response);
      }
    const Eigen::MatrixXd dense_basis = Eigen::MatrixXd(basis);
    const Eigen::MatrixXd schur       = Eigen::MatrixXd(huu) - hxu_f.transpose() * response;
    const Eigen::MatrixXd reduced = project_to_psd(Eigen::MatrixXd(dense_basis.transpose() * schur * dense_basis));
    append(Eigen::SparseMatrix<double>(reduced.sparseView()), 0, 0, false, h);
  }

  template <int dim>
  void NestedOuterObjective<dim>::limit_step(const Eigen::VectorXd &, Eigen::VectorXd &dp) const
  {
    // Newton steps are trusted up to `trust` in the max norm of the reference step. Where the
    // outer Hessian nearly vanishes (flat, or concave once projected: the shift makes it
    // ~1e-300) the solve returns a huge or non-finite step: then steepest descent of that
    // length instead.
    const Eigen::VectorXd g_basis = setting_.basis.transpose() * derivatives_.gu;
    const Eigen::VectorXd g = setting_.basis * g_basis, du = setting_.basis * dp;
    if (!du.allFinite() || du.dot(g) >= 0)
      {
        dp = -trust_ / std::max(g.lpNorm<Eigen::Infinity>(), 1e-300) * g_basis;
        return;
      }
    const double length = du.lpNorm<Eigen::Infinity>();
    if (length > trust_)
      dp *= trust_ / length;
  }

  template <int dim>
  double NestedOuterObjective<dim>::max_step(const Eigen::VectorXd &p, const Eigen::VectorXd &dp)
  {
    return setting_.step_filter(reference(p), setting_.basis * dp);
  }

  template <int dim>
  double NestedOuterObjective<dim>::step_norm(const Eigen::VectorXd &dp) const
  {
    return (setting_.basis * dp).template lpNorm<Eigen::Infinity>();
  }

  template <int dim>
  JointOuterObjective<dim>::JointOuterObjective(const OuterSetting<dim> &setting, const Eigen::VectorXd &u0,
                                                const Eigen::VectorXd &z0)
    : setting_(setting)
    , u0_(u0)
    , z0_(z0)
  {}

  template <int dim>
  Eigen::VectorXd JointOuterObjective<dim>::reference(const Eigen::VectorXd &y) const
  {
    return u0_ + setting_.basis * y.tail(setting_.basis.cols());
  }

  template <int dim>
  Eigen::VectorXd JointOuterObjective<dim>::state(const Eigen::VectorXd &y) const
  {
    Eigen::VectorXd z = z0_;
    for (Eigen::Index a = 0; a < n_free(); ++a)
      z[setting_.free_state[a]] += y[a];
    return z;
  }

  template <int dim>
  void JointOuterObjective<dim>::begin_iteration(const Eigen::VectorXd &y)
  {
    setting_.terms.set_reference(reference(y));
    const Eigen::VectorXd z = state(y);
    derivatives_ = setting_.terms.reference_derivatives(z, setting_.terms.candidates_at(z), ReferenceBlock::exact, true);
  }

  template <int dim>
  double JointOuterObjective<dim>::value(const Eigen::VectorXd &y)
  {
    setting_.terms.set_reference(reference(y));
    const Eigen::VectorXd z = state(y);
    return setting_.terms.objective(z, setting_.terms.candidates_at(z));
  }

  template <int dim>
  void JointOuterObjective<dim>::gradient(const Eigen::VectorXd &, Eigen::VectorXd &g)
  {
    g.resize(size());
    for (Eigen::Index a = 0; a < n_free(); ++a)
      g[a] = derivatives_.gx[setting_.free_state[a]];
    g.tail(setting_.basis.cols()) = setting_.basis.transpose() * derivatives_.gu;
  }

  template <int dim>
  void JointOuterObjective<dim>::hessian(const Eigen::VectorXd &, Triplets &h, bool)
  {
    const auto                       &d     = derivatives_;
    const Eigen::SparseMatrix<double> &basis = setting_.basis;
    const Eigen::Index n_f = n_free(), n_u = basis.rows(), n_z = d.gx.size();
    Triplets           select;  // state entries <- free entries
    for (Eigen::Index a = 0; a < n_f; ++a)
      select.emplace_back(setting_.free_state[a], a, 1.0);
    const Eigen::SparseMatrix<double> S = to_sparse(select, n_z, n_f);
    const Eigen::SparseMatrix<double> hxu = S.transpose() * to_sparse(d.hxu, n_z, n_u) * basis;
    append(S.transpose() * to_sparse(d.hxx, n_z, n_z) * S, 0, 0, false, h);
    append(hxu, 0, n_f, false, h);
    append(hxu, 0, n_f, true, h);
    append(basis.transpose() * to_sparse(d.huu, n_u, n_u) * basis, n_f, n_f, false, h);
  }

  template <int dim>
  double JointOuterObjective<dim>::max_step(const Eigen::VectorXd &y, const Eigen::VectorXd &dy)
  {
    return setting_.step_filter(reference(y), setting_.basis * dy.tail(setting_.basis.cols()));
  }

  template <int dim>
  double JointOuterObjective<dim>::step_norm(const Eigen::VectorXd &dy) const
  {
    return std::max(dy.head(n_free()).template lpNorm<Eigen::Infinity>(),
                    (setting_.basis * dy.tail(setting_.basis.cols())).template lpNorm<Eigen::Infinity>());
  }

  template class NestedOuterObjective<1>;
  template class NestedOuterObjective<2>;
  template class NestedOuterObjective<3>;
  template class JointOuterObjective<1>;
  template class JointOuterObjective<2>;
  template class JointOuterObjective<3>;
} // namespace ritr
