#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/common/psd_projection.h>
#include <ritr/common/wall_clock.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <optional>

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

    // Unit vectors spanning the plane normal to n (dim - 1 of them).
    template <int dim>
    std::vector<Vec<dim>> tangents_of(const Vec<dim> &n)
    {
      if constexpr (dim == 2)
        return {Vec<dim>(-n[1], n[0])};
      else if constexpr (dim == 3)
        {
          const Vec<dim> a = n.unitOrthogonal();
          return {a, n.cross(a).normalized()};
        }
      else
        return {};
    }
  } // namespace

  template <int dim>
  RitrSolver<dim>::RitrSolver(const SimplexMesh<dim> &mesh, BulkEnergy<dim> &bulk, ContactPotential<dim> *contact,
                              ImplicitStep<dim> &inner, const RitrSettings &settings,
                              const SimplexQuadrature<dim> &quadrature)
    : mesh_(mesh)
    , contact_(contact)
    , inner_(inner)
    , settings_(settings)
    , objective_(mesh, bulk, contact, quadrature, settings.inertia, settings.projection)
    , sliding_(classify_sliding(mesh, settings.sliding_tolerance))
    , youngs_modulus_(bulk.cell_material(0).youngs_modulus)
  {
    const std::vector<bool> &kinematic = inner.kinematic();
    Triplets                 directions;
    Eigen::Index             m = 0;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        bool prescribed = false;
        for (int k = 0; k < dim; ++k)
          prescribed = prescribed || kinematic[i * dim + k];
        if (prescribed)
          continue;  // a Dirichlet node keeps its reference position (its target depends on it)
        std::vector<Vec<dim>> allowed;
        const SlidingKind     kind = settings.geometric_admissibility ? sliding_[i].kind : SlidingKind::interior;
        if (kind == SlidingKind::interior)
          for (int k = 0; k < dim; ++k)
            allowed.push_back(Vec<dim>::Unit(k));
        else if (kind == SlidingKind::facet)
          allowed = tangents_of<dim>(sliding_[i].direction);
        else if (kind == SlidingKind::edge)
          allowed = {sliding_[i].direction};
        for (const auto &a : allowed)
          {
            for (int k = 0; k < dim; ++k)
              if (a[k] != 0)
                directions.emplace_back(i * dim + k, m, a[k]);
            ++m;
          }
      }
    basis_ = to_sparse(directions, mesh.reference.size(), m);
    for (std::size_t i = 0; i < kinematic.size(); ++i)
      if (!kinematic[i])
        free_state_.push_back(i);
    w_hat_ = std::numeric_limits<double>::max();
    for (const auto &cell : mesh.cells)
      w_hat_ = std::min(w_hat_, 0.1 * simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell)));
  }

  template <int dim>
  bool RitrSolver<dim>::solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z, const Eigen::VectorXd &targets,
                                      Result &r, const bool near_solution)
  {
    ScopedTimer timer(r.inner_seconds);
    objective_.set_candidate(u);
    inner_.set_linear_term(objective_.linear_term());
    try
      {
        r.inner_iterations += inner_.solve_on_mesh(u, z, targets, near_solution).iterations;
        return true;
      }
    catch (const ConvergenceError &)
      {
        return false;  // the trial mesh is rejected like one that raises R
      }
  }

  template <int dim>
  double RitrSolver<dim>::step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du) const
  {
    if (!settings_.geometric_admissibility)
      return 1.0;
    const auto admissible = [&](const double alpha) {
      const Eigen::VectorXd trial = u + alpha * du;
      for (const auto &cell : mesh_.cells)
        if (simplex_measure<dim, double>(cell_nodes<dim>(trial, cell)) <
            0.2 * simplex_measure<dim, double>(cell_nodes<dim>(u, cell)))
          return false;
      return true;
    };
    double alpha = 1.0;
    while (alpha > 1e-12 && !(admissible(alpha) && admissible(0.5 * alpha)))
      alpha *= 0.5;
    return alpha;
  }

  template <int dim>
  Eigen::SparseMatrix<double>
  RitrSolver<dim>::outer_hessian(const typename RitrObjective<dim>::Derivatives &d) const
  {
    const Eigen::Index                n_u = basis_.rows();
    const Eigen::SparseMatrix<double> huu = to_sparse(d.huu, n_u, n_u);
    if (settings_.hessian == RitrHessian::truncated)
      return basis_.transpose() * huu * basis_;

    // Schur complement on the free state entries: S = H_uu - H_xu^T H_xx^{-1} H_xu.
    const Eigen::Index n_z = d.gx.size(), n_f = free_state_.size();
    const Eigen::MatrixXd hxx = Eigen::MatrixXd(to_sparse(d.hxx, n_z, n_z));
    const Eigen::MatrixXd hxu = Eigen::MatrixXd(to_sparse(d.hxu, n_z, n_u));
    Eigen::MatrixXd       hxx_f(n_f, n_f), hxu_f(n_f, n_u);
    for (Eigen::Index a = 0; a < n_f; ++a)
      {
        hxu_f.row(a) = hxu.row(free_state_[a]);
        for (Eigen::Index b = 0; b < n_f; ++b)
          hxx_f(a, b) = hxx(free_state_[a], free_state_[b]);
      }
    Eigen::MatrixXd response = hxx_f.ldlt().solve(hxu_f);  // -dx/du
    if (settings_.hessian == RitrHessian::filtered)
      {
        const double threshold = settings_.filter_threshold * response.cwiseAbs().maxCoeff();
        response = (response.array().abs() < threshold).select(0.0, response);
      }
    const Eigen::MatrixXd dense_basis = Eigen::MatrixXd(basis_);
    const Eigen::MatrixXd schur       = Eigen::MatrixXd(huu) - hxu_f.transpose() * response;
    const Eigen::MatrixXd reduced     = project_to_psd(Eigen::MatrixXd(dense_basis.transpose() * schur * dense_basis));
    return reduced.sparseView();
  }

  template <int dim>
  Eigen::VectorXd RitrSolver<dim>::solve_outer(const Eigen::SparseMatrix<double> &H, const Eigen::VectorXd &rhs,
                                               Result &r)
  {
    ScopedTimer                 timer(r.outer_solve_seconds);
    Eigen::SparseMatrix<double> lower = H.template triangularView<Eigen::Lower>();
    lower.makeCompressed();
    cholesky_.factorize(lower);
    return cholesky_.solve(rhs);
  }

  template <int dim>
  typename RitrSolver<dim>::Result RitrSolver<dim>::step(const StepContext<dim> &step)
  {
    const Eigen::VectorXd &u_t = step.u_start, &z_t = step.z_start, &targets = step.targets;
    const double           h = step.time_step;
    const bool             dynamic = step.dynamic;
    const Eigen::Index    n_u = u_t.size();
    const Eigen::VectorXd x_t = z_t.head(n_u);
    const double          transfer_before = objective_.transfer_seconds();
    objective_.begin_step(step);

    Result r;
    r.u = u_t;
    r.z = z_t;
    // Physical admissibility at the start-of-step mesh: this also sets the contact stiffness
    // and lags friction for the whole step.
    {
      ScopedTimer timer(r.inner_seconds);
      objective_.set_candidate(u_t);
      inner_.set_linear_term(objective_.linear_term());
      r.inner_iterations += inner_.solve_start_of_step(step, r.z).iterations;
    }
    // The measure barrier's stiffness matches the contact barrier's (paper 5.3.2); without
    // contact it is the elastic stiffness per unit measure at the threshold w_hat.
    double kappa_w = settings_.measure_barrier_stiffness;
    if (kappa_w <= 0)
      kappa_w = contact_ ? contact_->stiffness() : (dynamic ? h * h : 1.0) * youngs_modulus_ / w_hat_;
    measure_stiffness_ = settings_.geometric_admissibility ? kappa_w : 0.0;
    objective_.set_measure_barrier(measure_stiffness_, w_hat_);
    r.initial_objective = r.objective = objective_.value(r.z, r.u);

    if (settings_.physical_admissibility && settings_.hessian == RitrHessian::reduced)
      trust_region_solve(targets, r);
    else if (settings_.physical_admissibility)
      nested_solve(targets, r);
    else
      joint_solve(targets, r);

    objective_.set_candidate(r.u);  // leave the contact weights on the accepted mesh
    r.sliding_violation = settings_.geometric_admissibility ? sliding_violation(sliding_, r.u) : 0.0;
    r.v = dynamic ? Eigen::VectorXd((r.z.head(n_u) - objective_.project(x_t, r.u)) / h) : Eigen::VectorXd::Zero(n_u);
    r.transfer_seconds = objective_.transfer_seconds() - transfer_before;
    return r;
  }

  template <int dim>
  template <typename Direction, typename Evaluate, typename Accept>
  void RitrSolver<dim>::descend(Result &r, const Direction &direction, const Evaluate &evaluate,
                                const Accept &accept) const
  {
    for (; r.outer_iterations < settings_.max_outer_iterations; ++r.outer_iterations)
      {
        const std::optional<double> first_fraction = direction();
        if (!first_fraction)
          {
            r.stop = OuterStop::converged;
            return;
          }
        // Backtracking by halves on R: a trial is taken as soon as R does not increase.
        bool decreased = false;
        double alpha = *first_fraction;
        for (; alpha > 1e-12; alpha *= 0.5)
          {
            ++r.line_search_trials;
            const double trial_objective = evaluate(alpha);
            if (trial_objective <= r.objective)
              {
                r.objective = trial_objective;
                decreased   = true;
                break;
              }
          }
        if (!decreased)
          {
            // No decrease along a descent direction: R is flat to round-off here, or the
            // direction is poor. The caller decides which; it is not called convergence.
            r.stop = OuterStop::no_decrease;
            return;
          }
        accept(alpha);
      }
    r.stop = OuterStop::iteration_limit;
  }

  template <int dim>
  void RitrSolver<dim>::nested_solve(const Eigen::VectorXd &targets, Result &r)
  {
    const bool      truncated = settings_.hessian == RitrHessian::truncated;
    Eigen::VectorXd du, u_trial, z_trial;
    const auto direction = [&]() -> std::optional<double> {
      objective_.set_candidate(r.u);
      const auto d = objective_.derivatives(
        r.z, r.u, truncated ? ReferenceBlock::following : ReferenceBlock::exact, !truncated);
      const Eigen::VectorXd g_reduced = basis_.transpose() * d.gu;
      const Eigen::VectorXd g         = basis_ * g_reduced;
      du                              = basis_ * solve_outer(outer_hessian(d), -g_reduced, r);
      // Newton steps are trusted up to half the initial smallest cell size. Where the outer
      // Hessian nearly vanishes (flat, or concave once projected) the solve returns a huge
      // or non-finite step: then steepest descent of that length instead.
      const double trust = 0.5 * std::pow(10 * w_hat_, 1.0 / dim);
      if (!du.allFinite() || du.dot(g) >= 0)
        du = -trust / std::max(g.lpNorm<Eigen::Infinity>(), 1e-300) * g;
      else if (du.lpNorm<Eigen::Infinity>() > trust)
        du *= trust / du.lpNorm<Eigen::Infinity>();
      if (du.lpNorm<Eigen::Infinity>() <= settings_.epsilon_r)
        return std::nullopt;
      return step_filter(r.u, du);  // the largest step that keeps the reference mesh admissible
    };
    // Every trial mesh re-solves the implicit step, warm-started from the current x; a mesh
    // where that fails is rejected like one that raises R.
    const auto evaluate = [&](const double alpha) {
      u_trial = r.u + alpha * du;
      z_trial = r.z;
      if (!solve_on_mesh(u_trial, z_trial, targets, r))
        return std::numeric_limits<double>::infinity();
      return objective_.value(z_trial, u_trial);
    };
    const auto accept = [&](double) {
      r.u = u_trial;
      r.z = z_trial;
    };
    descend(r, direction, evaluate, accept);
  }

  template <int dim>
  void RitrSolver<dim>::trust_region_solve(const Eigen::VectorXd &targets, Result &r)
  {
    // Radii are lengths (outer_model.h); the first is the old fixed cap, half the smallest
    // initial cell, and the region may grow to a hundred of them.
    const double initial_radius = 0.5 * std::pow(10 * w_hat_, 1.0 / dim);
    const double max_radius     = 100 * initial_radius;
    double       radius         = initial_radius;
    double       first_gradient = 0;
    MeasureBarrierModel<dim> barrier(mesh_, basis_, w_hat_, measure_stiffness_);
    const auto filter = [&](const Eigen::VectorXd &du) { return step_filter(r.u, du); };
    for (; r.outer_iterations < settings_.max_outer_iterations; ++r.outer_iterations)
      {
        objective_.set_candidate(r.u);
        const auto d = objective_.derivatives(r.z, r.u, ReferenceBlock::exact, true);
        const Eigen::VectorXd g = basis_.transpose() * d.gu;
        if (r.outer_iterations == 0)
          first_gradient = g.norm();
        std::optional<ReducedHessian>   hessian;
        std::optional<OuterModel<dim>> model;
        {
          ScopedTimer timer(r.outer_solve_seconds);
          hessian.emplace(d.huu, d.hxx, d.hxu, r.z.size(), free_state_, basis_, state_cholesky_);
          barrier.set_point(r.u);
          model.emplace(*hessian, barrier, g, basis_, preconditioner_);
        }
        // Inexact Newton: the CG residual relative to |g| shrinks with |g| (superlinear
        // convergence without oversolving far from the minimum).
        const double forcing   = std::min(0.1, std::sqrt(g.norm() / std::max(first_gradient, 1e-300)));
        const double round_off = 1e-13 * std::max(1.0, std::abs(r.objective));
        for (bool accepted = false; !accepted;)
          {
            typename OuterModel<dim>::Step step;
            {
              ScopedTimer timer(r.outer_solve_seconds);
              step = model->propose(radius, forcing, settings_.epsilon_r, filter, barrier);
            }
            if (step.converged)
              {
                r.stop = OuterStop::converged;
                return;
              }
            // Far from a Newton step R may still fall for hundreds of iterations along nearly
            // flat directions (nodes sliding past the measure barrier): on the 205-vertex bar
            // the first 20 iterations made 97 % of what 200 made.
            if (step.predicted > -settings_.decrease_tolerance * (r.initial_objective - r.objective))
              {
                r.stop = OuterStop::small_decrease;
                return;
              }
            if (!(step.predicted < -round_off))
              {
                // R cannot resolve the step. A Newton step, or any step in a region of the
                // initial size or larger, means R is flat to round-off at the scale of a cell
                // (a body in free flight): converged. Otherwise a smaller region is tried,
                // whose direction leans towards steepest descent.
                if (step.newton || radius >= initial_radius)
                  {
                    r.stop = OuterStop::converged;
                    return;
                  }
                radius = 0.25 * model->length(step.p);
              }
            else
              {
                const auto [trial_objective, u_trial, z_trial] = trial(step, *hessian, targets, r);
                const double rho         = (trial_objective - r.objective) / step.predicted;
                const double step_length = model->length(step.p);
                if (!(rho >= 0.25))
                  radius = 0.25 * step_length;
                else if (rho > 0.75 && step_length >= 0.99 * radius)
                  radius = std::min(2 * radius, max_radius);
                accepted = rho >= 0.05 && trial_objective <= r.objective;
                if (accepted)
                  {
                    r.u         = u_trial;
                    r.z         = z_trial;
                    r.objective = trial_objective;
                  }
              }
            if (!accepted && radius <= 1e-3 * settings_.epsilon_r)
              {
                r.stop = OuterStop::no_decrease;  // no region small enough gave a decrease
                return;
              }
          }
      }
    r.stop = OuterStop::iteration_limit;
  }

  template <int dim>
  std::tuple<double, Eigen::VectorXd, Eigen::VectorXd>
  RitrSolver<dim>::trial(const typename OuterModel<dim>::Step &step, const ReducedHessian &hessian,
                         const Eigen::VectorXd &targets, Result &r)
  {
    ++r.line_search_trials;
    const Eigen::VectorXd u = r.u + step.du;
    // The state at the trial mesh to first order, kept short of any contact; the inner Newton
    // polishes it (starting with the exact Hessian, which converges from there in ~2 steps).
    Eigen::VectorXd dz = hessian.state_response(step.p);
    if (contact_)
      dz *= std::min(1.0, 0.9 * contact_->max_step(r.z, dz));
    Eigen::VectorXd z      = r.z + dz;
    bool            solved = solve_on_mesh(u, z, targets, r, true);
    if (!solved)
      {
        z      = r.z;  // a poor prediction: the warm start of the backtracking path
        solved = solve_on_mesh(u, z, targets, r);
      }
    return {solved ? objective_.value(z, u) : std::numeric_limits<double>::infinity(), u, z};
  }

  template <int dim>
  void RitrSolver<dim>::joint_solve(const Eigen::VectorXd &targets, Result &r)
  {
    if (contact_)
      throw std::invalid_argument("r-adaptivity without physical admissibility is implemented without contact only");
    for (Eigen::Index i = 0; i < r.z.size(); ++i)
      if (inner_.kinematic()[i])
        r.z[i] = targets[i];
    const Eigen::Index n_f = free_state_.size(), n_b = basis_.cols(), n_u = basis_.rows(), n_z = r.z.size();
    Triplets           select;  // state entries <- free entries
    for (Eigen::Index a = 0; a < n_f; ++a)
      select.emplace_back(free_state_[a], a, 1.0);
    const Eigen::SparseMatrix<double> S = to_sparse(select, n_z, n_f);

    Eigen::VectorXd dz, du;
    const auto direction = [&]() -> std::optional<double> {
      objective_.set_candidate(r.u);
      auto d = objective_.derivatives(r.z, r.u, ReferenceBlock::exact, true);
      Eigen::VectorXd g(n_f + n_b);
      g << S.transpose() * d.gx, basis_.transpose() * d.gu;
      const Eigen::SparseMatrix<double> hxx = S.transpose() * to_sparse(d.hxx, n_z, n_z) * S;
      const Eigen::SparseMatrix<double> hxu = S.transpose() * to_sparse(d.hxu, n_z, n_u) * basis_;
      const Eigen::SparseMatrix<double> huu = basis_.transpose() * to_sparse(d.huu, n_u, n_u) * basis_;
      Triplets                          blocks;
      const auto add = [&](const Eigen::SparseMatrix<double> &m, Eigen::Index r0, Eigen::Index c0, bool transpose) {
        for (int k = 0; k < m.outerSize(); ++k)
          for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
            transpose ? blocks.emplace_back(c0 + it.col(), r0 + it.row(), it.value()) :
                        blocks.emplace_back(r0 + it.row(), c0 + it.col(), it.value());
      };
      add(hxx, 0, 0, false);
      add(hxu, 0, n_f, false);
      add(hxu, 0, n_f, true);
      add(huu, n_f, n_f, false);
      const Eigen::VectorXd step = solve_outer(to_sparse(blocks, n_f + n_b, n_f + n_b), -g, r);
      dz = S * step.head(n_f);
      du = basis_ * step.tail(n_b);
      if (std::max(dz.lpNorm<Eigen::Infinity>(), du.lpNorm<Eigen::Infinity>()) <= settings_.epsilon_r)
        return std::nullopt;
      return step_filter(r.u, du);
    };
    const auto evaluate = [&](const double alpha) {
      objective_.set_candidate(r.u + alpha * du);
      return objective_.value(r.z + alpha * dz, r.u + alpha * du);
    };
    const auto accept = [&](const double alpha) {
      r.u += alpha * du;
      r.z += alpha * dz;
    };
    descend(r, direction, evaluate, accept);
  }

  template class RitrSolver<1>;
  template class RitrSolver<2>;
  template class RitrSolver<3>;
} // namespace ritr
