#include <ritr/adaptivity/line_search_outer.h>
#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/common/wall_clock.h>
#include <ritr/solver/steihaug_cg.h>
#include <ritr/terms/contact_barrier_term.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace ritr
{
  namespace
  {
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
  RitrSolver<dim>::RitrSolver(const CellMaterials<dim> &materials, ImplicitStep<dim> &inner,
                              const RitrSettings &settings, const SimplexQuadrature<dim> &quadrature)
    : mesh_(materials.mesh())
    , terms_(inner.terms())
    , inner_(inner)
    , settings_(settings)
    , measure_barrier_(*inner.terms().template find<MeasureBarrierTerm<dim>>())
    , inertia_(inner.terms().template find<TransferredInertiaTerm<dim>>())
    , velocity_transfer_(materials.mesh().cells, quadrature, settings.transfer_integration)
    , sliding_(classify_sliding(materials.mesh(), settings.sliding_tolerance))
    , carrier_(materials.mesh())
    , w_hat_(measure_barrier_.threshold())
    , youngs_modulus_(materials.of_cell(0).youngs_modulus)
  {
    const std::vector<bool> &kinematic = inner.kinematic();
    // Sliding Dirichlet nodes move along their condition's boundary only: a node at its end
    // (on a facet with a node outside the condition) would carry the condition onto free
    // boundary, and an interior one into material the condition does not hold.
    std::vector<int> condition(mesh_.n_nodes(), -1);
    for (const auto &[n, d] : settings.sliding_dirichlet_nodes)
      if (sliding_[n].kind == SlidingKind::facet || sliding_[n].kind == SlidingKind::edge)
        condition[n] = d;
    std::vector<bool> slides(mesh_.n_nodes(), false);
    if (settings.geometric_admissibility)
      {
        for (unsigned int n = 0; n < mesh_.n_nodes(); ++n)
          slides[n] = condition[n] >= 0;
        // Every facet through a sliding node lies on its condition (one condition: two with
        // different displacements meet at a node that must stay).
        for (const auto &facet : mesh_.boundary_facets)
          if (!std::all_of(facet.begin(), facet.end(),
                           [&](const unsigned int n) { return condition[n] >= 0 && condition[n] == condition[facet[0]]; }))
            for (const unsigned int n : facet)
              slides[n] = false;
      }
    Triplets     directions;
    Eigen::Index m = 0;
    for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
      {
        bool prescribed = false;
        for (int k = 0; k < dim; ++k)
          prescribed = prescribed || kinematic[i * dim + k];
        if (prescribed && !slides[i])
          continue;  // a Dirichlet node keeps its reference position (its target depends on it)
        if (slides[i])
          for (int k = 0; k < dim; ++k)
            following_prescribed_.push_back(i * dim + k);
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
    basis_.resize(mesh_.reference.size(), m);
    basis_.setFromTriplets(directions.begin(), directions.end());
    for (std::size_t i = 0; i < kinematic.size(); ++i)
      if (!kinematic[i])
        free_state_.push_back(i);
  }

  Eigen::VectorXd sliding_dirichlet_targets(const Eigen::VectorXd &targets, const Eigen::VectorXd &u,
                                            const Eigen::VectorXd &initial_reference, const std::vector<int> &entries)
  {
    Eigen::VectorXd moved = targets;
    for (const int e : entries)
      moved[e] += u[e] - initial_reference[e];
    return moved;
  }

  template <int dim>
  Eigen::VectorXd RitrSolver<dim>::targets_at(const Eigen::VectorXd &targets, const Eigen::VectorXd &u) const
  {
    return sliding_dirichlet_targets(targets, u, mesh_.reference, following_prescribed_);
  }

  template <int dim>
  double RitrSolver<dim>::transfer_seconds() const
  {
    return velocity_transfer_seconds_ + (inertia_ ? inertia_->transfer_seconds() : 0.0);
  }

  template <int dim>
  double RitrSolver<dim>::objective(const Eigen::VectorXd &z, const Eigen::VectorXd &u)
  {
    terms_.set_reference(u);
    return terms_.objective(z, terms_.candidates_at(z));
  }

  template <int dim>
  std::optional<bool> RitrSolver<dim>::solve_on_mesh(const Eigen::VectorXd &u, Eigen::VectorXd &z,
                                                     const Eigen::VectorXd &targets, Result &r, const bool near_solution,
                                                     const double tolerance_scale, const unsigned int iteration_cap)
  {
    ScopedTimer timer(r.inner_seconds);
    try
      {
        const auto report = inner_.solve_on_mesh(u, z, targets, near_solution, tolerance_scale, iteration_cap);
        r.inner_iterations += report.iterations;
        return report.converged;
      }
    catch (const ConvergenceError &)
      {
        return std::nullopt;  // the trial mesh is rejected like one that raises R
      }
  }

  template <int dim>
  double RitrSolver<dim>::step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du) const
  {
    return step_filter(u, Eigen::VectorXd::Zero(du.size()), du);
  }

  template <int dim>
  double RitrSolver<dim>::step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du,
                                      const Eigen::VectorXd &ddu) const
  {
    if (!settings_.geometric_admissibility)
      return 1.0;
    std::vector<double> floor(mesh_.n_cells());
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      floor[c] = 0.2 * simplex_measure<dim, double>(cell_nodes<dim>(u, mesh_.cells[c]));
    const auto admissible = [&](const double alpha) {
      const Eigen::VectorXd trial = u + du + alpha * ddu;
      for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
        if (simplex_measure<dim, double>(cell_nodes<dim>(trial, mesh_.cells[c])) < floor[c])
          return false;
      return true;
    };
    double alpha = 1.0;
    while (alpha > 1e-12 && !(admissible(alpha) && admissible(0.5 * alpha)))
      alpha *= 0.5;
    return alpha;
  }

  template <int dim>
  typename RitrSolver<dim>::Result RitrSolver<dim>::step(const StepContext<dim> &step)
  {
    const Eigen::VectorXd &u_t = step.u_start, &z_t = step.z_start;
    const Eigen::VectorXd  targets = step.targets;  // at the initial reference (targets_at)
    const double           h = step.time_step;
    const bool             dynamic = step.dynamic;
    const Eigen::Index     n_u = u_t.size();
    const double           transfer_before = transfer_seconds();

    Result r;
    r.u = u_t;
    r.z = z_t;
    // Physical admissibility at the start-of-step mesh: this also starts the step for every
    // term, sets the contact stiffness and lags friction for the whole step.
    {
      ScopedTimer      timer(r.inner_seconds);
      StepContext<dim> start = step;
      start.targets          = targets_at(targets, u_t);
      r.inner_iterations += inner_.solve_start_of_step(start, r.z).iterations;
    }
    // The measure barrier's stiffness matches the contact barrier's (paper 5.3.2); without
    // contact it is the elastic stiffness per unit measure at the threshold w_hat.
    double kappa_w = settings_.measure_barrier_stiffness;
    if (kappa_w <= 0)
      {
        const auto *barrier = terms_.template find<ContactBarrierTerm<dim>>();
        kappa_w = barrier ? barrier->stiffness() : (dynamic ? h * h : 1.0) * youngs_modulus_ / w_hat_;
      }
    measure_barrier_.set_stiffness(settings_.geometric_admissibility ? kappa_w : 0.0);
    r.initial_objective = r.objective = objective(r.z, r.u);

    if (settings_.physical_admissibility && is_trust_region(settings_.hessian))
      trust_region_solve(targets, r);
    else
      line_search_solve(targets, r);

    terms_.set_reference(r.u);  // leave the contact weights on the accepted mesh
    r.sliding_violation = settings_.geometric_admissibility ? sliding_violation(sliding_, r.u) : 0.0;
    if (dynamic)
      {
        ScopedTimer timer(velocity_transfer_seconds_);
        // The inertia's transfer is already set up from u_t to the accepted mesh: its operator
        // projects x_t as well.
        if (inertia_ && inertia_->transfer().candidate() == r.u)
          r.v = (r.z.head(n_u) - inertia_->transfer().project(z_t.head(n_u))) / h;
        else
          {
            velocity_transfer_.set_old_mesh(u_t);
            r.v = (r.z.head(n_u) - velocity_transfer_.project(z_t.head(n_u), r.u)) / h;
          }
      }
    else
      r.v = Eigen::VectorXd::Zero(n_u);
    r.transfer_seconds = transfer_seconds() - transfer_before;
    return r;
  }

  template <int dim>
  Eigen::VectorXd RitrSolver<dim>::carried_state() const
  {
    const Eigen::VectorXd curvature = quasi_newton_.state();
    Eigen::VectorXd       state(1 + curvature.size());
    state << carried_radius_, curvature;
    return state;
  }

  template <int dim>
  void RitrSolver<dim>::restore_carried_state(const Eigen::VectorXd &state)
  {
    if (state.size() < 1)
      throw std::invalid_argument("no r-ITR solver state");
    carried_radius_ = state[0];
    quasi_newton_.restore(state.tail(state.size() - 1), basis_.cols());
  }

  template <int dim>
  void RitrSolver<dim>::line_search_solve(const Eigen::VectorXd &targets, Result &r)
  {
    const OuterSetting<dim> setting{
      terms_, basis_, free_state_,
      [&](const Eigen::VectorXd &u, Eigen::VectorXd &z) { return solve_on_mesh(u, z, targets, r).has_value(); },
      [&](const Eigen::VectorXd &u, const Eigen::VectorXd &du) { return step_filter(u, du); }};
    const NewtonSettings newton = outer_newton_settings(settings_.epsilon_r, settings_.max_outer_iterations);
    const double         linear_before = outer_newton_.seconds_in_linear_solves();
    NewtonResult         result;
    if (settings_.physical_admissibility)
      {
        // Steps are trusted up to half the initial smallest cell size.
        const double trust = 0.5 * std::pow(10 * w_hat_, 1.0 / dim);
        NestedOuterObjective<dim> outer(setting, settings_.hessian, settings_.filter_threshold, trust, r.u, r.z,
                                        r.objective);
        Eigen::VectorXd p = Eigen::VectorXd::Zero(basis_.cols());
        result   = outer_newton_.minimize(outer, p, std::vector<bool>(p.size(), false), p, newton);
        r.u         = outer.reference(p);
        r.z         = outer.state();
        r.objective = outer.objective();
      }
    else
      {
        if (terms_.has_contact())
          throw std::invalid_argument("r-adaptivity without physical admissibility is implemented without contact only");
        for (Eigen::Index i = 0; i < r.z.size(); ++i)
          if (inner_.kinematic()[i])
            r.z[i] = targets[i];
        JointOuterObjective<dim> outer(setting, r.u, r.z);
        Eigen::VectorXd y = Eigen::VectorXd::Zero(outer.size());
        result = outer_newton_.minimize(outer, y, std::vector<bool>(y.size(), false), y, newton);
        r.u         = outer.reference(y);
        r.z         = outer.state(y);
        r.objective = objective(r.z, r.u);
      }
    r.outer_iterations += result.iterations;
    r.line_search_trials += result.line_search_trials;
    r.outer_solve_seconds += outer_newton_.seconds_in_linear_solves() - linear_before;
    // A search that found no decrease along a descent direction: R is flat to round-off
    // there, or the direction is poor. It is reported, not called convergence.
    r.stop = result.status == NewtonStatus::converged       ? OuterStop::converged :
             result.status == NewtonStatus::iteration_limit ? OuterStop::iteration_limit :
                                                              OuterStop::no_decrease;
  }

  template <int dim>
  void RitrSolver<dim>::trust_region_solve(const Eigen::VectorXd &targets, Result &r)
  {
    state_loose_ = tight_only_ = false;
    pair_start_.resize(0);
    trust_region_iterations(targets, r);
    if (state_loose_)
      {
        // The accepted state was solved loosely, and the outer stop judged its gradient, which
        // assumes an exact inner solve: solve tightly at the accepted mesh, then go on with
        // tight trials until the outer solve stops again.
        if (!solve_on_mesh(r.u, r.z, targets_at(targets, r.u), r, true))
          throw ConvergenceError("the tight inner solve at the accepted mesh failed");
        r.objective  = objective(r.z, r.u);
        state_loose_ = false;
        tight_only_  = true;
        if (r.outer_iterations < settings_.max_outer_iterations)
          trust_region_iterations(targets, r);
      }
    // The gradient at the step's end completes a curvature pair, so that pairs accumulate
    // across steps even when each takes one outer iteration.
    if (pair_start_.size() > 0 && pair_start_ != r.u)
      curvature_pair_to(r.u, reduced_gradient(r.z, r.u, true));
  }

  template <int dim>
  void RitrSolver<dim>::curvature_pair_to(const Eigen::VectorXd &u, const Eigen::VectorXd &rest_gradient)
  {
    // The basis's columns are orthonormal, so B^T takes a reference step to its coordinates.
    if (pair_start_.size() > 0)
      quasi_newton_.update(basis_.transpose() * (u - pair_start_), rest_gradient - pair_gradient_);
    pair_start_    = u;
    pair_gradient_ = rest_gradient;
  }

  template <int dim>
  void RitrSolver<dim>::trust_region_iterations(const Eigen::VectorXd &targets, Result &r)
  {
    // Radii are lengths (outer_model.h); the first is the old fixed cap, half the smallest
    // initial cell, and the region may grow to a hundred of them.
    const double initial_radius = 0.5 * std::pow(10 * w_hat_, 1.0 / dim);
    const double max_radius     = 100 * initial_radius;
    // Quasi-Newton steps take one or two outer iterations, so the region a step ends with is
    // where the next one starts (never below the initial radius), and reduced-first's quasi-Newton
    // iterations go on in it. The reduced solve carries it on request: with one iteration per
    // step and a fresh region each step, the masticator's mesh could not follow the bar by more
    // than half a cell per step.
    const bool carries_region = settings_.hessian != RitrHessian::reduced || settings_.carry_trust_region;
    double     step_radius    = initial_radius;
    double    &radius         = carries_region ? carried_radius_ : step_radius;
    radius                    = std::max(radius, initial_radius);
    double       first_gradient = 0;
    MeasureBarrierModel<dim> barrier(mesh_, basis_, w_hat_, measure_barrier_.stiffness());
    const auto filter = [&](const Eigen::VectorXd &du, const Eigen::VectorXd &ddu) {
      return step_filter(r.u, du, ddu);
    };
    for (; r.outer_iterations < settings_.max_outer_iterations; ++r.outer_iterations)
      {
        terms_.set_reference(r.u);
        const bool quasi_newton = settings_.hessian == RitrHessian::quasi_newton ||
                                  (settings_.hessian == RitrHessian::reduced_first && r.outer_iterations > 0);
        Eigen::VectorXd                g;
        std::optional<ReducedHessian>  hessian;
        std::optional<OuterModel<dim>> model;
        if (quasi_newton)
          {
            const Eigen::VectorXd rest = reduced_gradient(r.z, r.u, true);
            ScopedTimer           timer(r.outer_solve_seconds);
            // A gradient at a state solved short of its tolerance is off by H_ux (x - x*), more
            // than the change a pair measures: pairs join tightly solved states only.
            if (!state_loose_)
              curvature_pair_to(r.u, rest);
            barrier.set_point(r.u);
            g = rest + barrier.at_point().gradient;
            quasi_newton_.with_barrier(barrier.at_point().hessian);
            if (quasi_newton_.empty())
              quasi_newton_.set_scale(g.norm() / initial_radius);  // steepest descent to the region's edge
            model.emplace(quasi_newton_, g, basis_);
          }
        else
          {
            auto d = terms_.reference_derivatives(r.z, terms_.candidates_at(r.z), ReferenceBlock::exact, true);
            fold_following_prescribed(following_prescribed_, d.gx, d.hxx, d.gu, d.huu, d.hxu);
            g = basis_.transpose() * d.gu;
            ScopedTimer timer(r.outer_solve_seconds);
            hessian.emplace(d.huu, d.hxx, d.hxu, r.z.size(), free_state_, basis_, state_cholesky_);
            barrier.set_point(r.u);
            model.emplace(*hessian, g, basis_);
          }
        if (r.outer_iterations == 0)
          first_gradient = g.norm();
        // The forcing term's cap (model tolerance) is tight by default because |g| often stays
        // near its first value while the mesh creeps along a flat valley: with a cap of 0.1 the
        // steps then left a tenth of the model's gradient each time, and late ball-on-spikes
        // steps took 76-200 iterations of ~1e-9 decrease each.
        const double forcing   = forcing_term(g.norm(), first_gradient, settings_.model_tolerance);
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
                const auto [trial_objective, u_trial, z_trial] =
                  trial(step, predicted_state_change(step, hessian, r.z, r.u), targets, r);
                const double rho         = (trial_objective - r.objective) / step.predicted;
                const double step_length = model->length(step.p);
                if (!(rho >= 0.25))
                  radius = 0.25 * step_length;
                else if (rho > 0.75 && step_length >= 0.99 * radius)
                  radius = std::min(2 * radius, max_radius);
                accepted = rho >= 0.05 && trial_objective <= r.objective;
                if (accepted)
                  {
                    r.u          = u_trial;
                    r.z          = z_trial;
                    r.objective  = trial_objective;
                    state_loose_ = last_trial_loose_;
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
  Eigen::VectorXd RitrSolver<dim>::reduced_gradient(const Eigen::VectorXd &z, const Eigen::VectorXd &u,
                                                    const bool without_measure_barrier)
  {
    terms_.set_reference(u);
    const CollisionCandidates candidates = terms_.candidates_at(z);
    Eigen::VectorXd           gu         = terms_.reference_gradient(z, candidates, without_measure_barrier);
    if (!following_prescribed_.empty())
      {
        // A sliding Dirichlet node's prescribed position moves with its reference (x_p = u_p + a
        // constant): the composition's gradient adds the state gradient there.
        Eigen::VectorXd gx = Eigen::VectorXd::Zero(z.size());
        terms_.add_energy_gradient(z, candidates, gx);
        for (const int e : following_prescribed_)
          gu[e] += gx[e];
      }
    return basis_.transpose() * gu;
  }

  template <int dim>
  Eigen::VectorXd RitrSolver<dim>::predicted_state_change(const typename OuterModel<dim>::Step &step,
                                                          const std::optional<ReducedHessian>   &hessian,
                                                          const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
  {
    // The implicit-function response of x to first order, or without the reduced Hessian's
    // factor the current deformation carried to the moved nodes (prescribed entries stay).
    if (hessian)
      return hessian->state_response(step.p);
    Eigen::VectorXd       dz = Eigen::VectorXd::Zero(z.size());
    const Eigen::VectorXd dx = carrier_.carried(z.head(u.size()), u, step.du);
    for (Eigen::Index i = 0; i < dx.size(); ++i)
      if (!inner_.kinematic()[i])
        dz[i] = dx[i];
    return dz;
  }

  template <int dim>
  std::tuple<double, Eigen::VectorXd, Eigen::VectorXd>
  RitrSolver<dim>::trial(const typename OuterModel<dim>::Step &step, Eigen::VectorXd dz,
                         const Eigen::VectorXd &targets, Result &r)
  {
    ++r.line_search_trials;
    const Eigen::VectorXd u = r.u + step.du;
    // The state at the trial mesh predicted (predicted_state_change), kept short of any
    // contact; the inner Newton polishes it (starting with the exact Hessian, which converges
    // from there in ~2 steps).
    for (const int e : following_prescribed_)
      dz[e] = step.du[e];
    if (terms_.has_contact())
      dz *= std::min(1.0, 0.9 * terms_.max_step(r.z, dz));
    Eigen::VectorXd       z            = r.z + dz;
    const Eigen::VectorXd trial_target = targets_at(targets, u);
    // Inexact inner solves in the spirit of Eisenstat and Walker: the state needs no more
    // accuracy than the outer step resolves, so the tolerance tightens as |du| falls to
    // epsilon r. R's error is second order in the state's, so the ratio test is unaffected.
    const double scale =
      tight_only_ || !(settings_.epsilon_r > 0) ?
        1.0 :
        std::clamp(step.du.template lpNorm<Eigen::Infinity>() / settings_.epsilon_r, 1.0,
                   std::max(1.0, settings_.inner_tolerance_factor));
    const unsigned int  cap    = tight_only_ ? 0 : settings_.trial_iterations;
    std::optional<bool> solved = solve_on_mesh(u, z, trial_target, r, true, scale, cap);
    if (!solved)
      {
        z      = r.z;  // a poor prediction: the warm start of the backtracking path
        solved = solve_on_mesh(u, z, trial_target, r, false, scale, cap);
      }
    // A state stopped short of its tolerance (loosened or capped): R there bounds R at the
    // mesh from above, so an accepted trial still lowers R.
    last_trial_loose_ = scale > 1 || (solved && !*solved);
    return {solved ? objective(z, u) : std::numeric_limits<double>::infinity(), u, z};
  }

  template class RitrSolver<1>;
  template class RitrSolver<2>;
  template class RitrSolver<3>;
} // namespace ritr
