#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/common/psd_projection.h>
#include <ritr/time/incremental_potential.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace ritr
{
  template <int dim>
  RitrSolver<dim>::RitrSolver(const SimplexMesh<dim> &mesh, const Material &material, const RitrSettings &settings,
                              const transfer::SimplexQuadrature<dim> &quadrature)
    : mesh_(mesh)
    , material_(material)
    , settings_(settings)
    , bulk_(mesh, std::vector<Material>(*std::max_element(mesh.cell_material.begin(), mesh.cell_material.end()) + 1,
                                        material))
    , transfer_(mesh.cells, quadrature)
    , sliding_(classify_sliding(mesh, settings.sliding_tolerance))
  {
    // Corners (and 1D rod ends) keep their reference position; every other node may move.
    u_fixed_.assign(mesh.reference.size(), false);
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      if (sliding_[i].kind == SlidingKind::corner)
        for (int k = 0; k < dim; ++k)
          u_fixed_[i * dim + k] = true;
    w_hat_ = 0.1 * std::numeric_limits<double>::max();
    for (const auto &cell : mesh.cells)
      w_hat_ = std::min(w_hat_, 0.1 * simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell)));
  }

  template <int dim>
  double RitrSolver<dim>::penalties(const Eigen::VectorXd &u, Eigen::VectorXd *g, Triplets *h) const
  {
    const double kappa = settings_.penalty_stiffness > 0 ? settings_.penalty_stiffness :
                                                           h_ * h_ * material_.youngs_modulus;
    return sliding_penalty(sliding_, u, kappa, g, h) + reference_measure_barrier(mesh_, u, w_hat_, kappa, g, h);
  }

  template <int dim>
  unsigned int RitrSolver<dim>::solve_inner(const Eigen::VectorXd &u, Eigen::VectorXd &x)
  {
    transfer_.set_candidate(u);
    IncrementalPotential<dim> potential(bulk_, nullptr, u);
    potential.set_linear_term(-material_.density * transfer_.gradient_x(predictor_));
    NewtonSettings settings;
    settings.tolerance = settings_.epsilon_e * h_;
    const NewtonResult r =
      newton_.minimize(potential, x, std::vector<bool>(x.size(), false), Eigen::VectorXd::Zero(x.size()), settings);
    if (!r.converged)
      throw std::runtime_error("r-ITR inner solve did not converge: " + r.failure);
    return r.iterations;
  }

  template <int dim>
  double RitrSolver<dim>::objective(const Eigen::VectorXd &x, const Eigen::VectorXd &u) const
  {
    return bulk_.value(x, u) - material_.density * transfer_.value(x, predictor_) + penalties(u, nullptr, nullptr);
  }

  template <int dim>
  double RitrSolver<dim>::step_filter(const Eigen::VectorXd &u, const Eigen::VectorXd &du) const
  {
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
  typename RitrSolver<dim>::Result RitrSolver<dim>::step(const Eigen::VectorXd &u_t, const Eigen::VectorXd &x_t,
                                                         const Eigen::VectorXd &v_t, const double h,
                                                         const std::array<double, dim> &gravity)
  {
    h_         = h;
    predictor_ = x_t + h * v_t;
    transfer_.set_old_mesh(u_t);
    CellEnergyWeights<dim> w;
    w.inertia   = 1.0;
    w.potential = h * h;
    w.gravity   = gravity;
    bulk_.set_weights(w);
    // The bulk term keeps only 1/2 x^T M(u) x; the predictor enters through the transfer.
    bulk_.set_predictor(Eigen::VectorXd::Zero(x_t.size()));

    Result r;
    r.u = u_t;
    r.x = x_t;
    r.inner_iterations += solve_inner(r.u, r.x);
    double current = objective(r.x, r.u);

    std::vector<int> free_index(r.u.size(), -1);
    int              n_free = 0;
    for (Eigen::Index i = 0; i < r.u.size(); ++i)
      if (!u_fixed_[i])
        free_index[i] = n_free++;
    SparseCholesky cholesky;
    for (; r.outer_iterations < settings_.max_outer_iterations; ++r.outer_iterations)
      {
        // Gradient and Hessian of R in u at x = argmin E(., u).
        const bool full = settings_.hessian == RitrHessian::full;
        typename BulkEnergy<dim>::JointDerivatives joint;
        bulk_.joint_derivatives(r.x, r.u, !full, joint);
        transfer_.set_candidate(r.u);
        Eigen::VectorXd g = joint.gu - material_.density * transfer_.gradient_u(r.x, predictor_);
        Triplets        hessian = std::move(joint.huu);
        transfer_.add_hessian_u(r.x, predictor_, -material_.density, !full, hessian);
        penalties(r.u, &g, &hessian);
        if (full)
          {
            // Schur complement S = H_uu - H_xu^T H_xx^{-1} H_xu, then Proj+ of S as a whole.
            const Eigen::Index n = r.u.size();
            Eigen::SparseMatrix<double> huu(n, n), hxu(n, n), hxx(n, n);
            huu.setFromTriplets(hessian.begin(), hessian.end());
            transfer_.add_hessian_xu(r.x, predictor_, -material_.density, joint.hxu);
            hxu.setFromTriplets(joint.hxu.begin(), joint.hxu.end());
            hxx.setFromTriplets(joint.hxx.begin(), joint.hxx.end());
            const Eigen::MatrixXd response = Eigen::MatrixXd(hxx).ldlt().solve(Eigen::MatrixXd(hxu));
            const Eigen::MatrixXd schur =
              project_to_psd(Eigen::MatrixXd(Eigen::MatrixXd(huu) - Eigen::MatrixXd(hxu).transpose() * response));
            hessian.clear();
            for (Eigen::Index i = 0; i < n; ++i)
              for (Eigen::Index j = 0; j < n; ++j)
                hessian.emplace_back(i, j, schur(i, j));
          }

        Triplets        reduced;
        Eigen::VectorXd rhs(n_free);
        for (Eigen::Index i = 0; i < r.u.size(); ++i)
          if (free_index[i] >= 0)
            rhs[free_index[i]] = -g[i];
        for (const auto &t : hessian)
          if (free_index[t.row()] >= 0 && free_index[t.col()] >= 0 && free_index[t.row()] >= free_index[t.col()])
            reduced.emplace_back(free_index[t.row()], free_index[t.col()], t.value());
        Eigen::SparseMatrix<double> H(n_free, n_free);
        H.setFromTriplets(reduced.begin(), reduced.end());
        H.makeCompressed();
        cholesky.factorize(H);
        const Eigen::VectorXd du_free = cholesky.solve(rhs);
        Eigen::VectorXd       du      = Eigen::VectorXd::Zero(r.u.size());
        for (Eigen::Index i = 0; i < r.u.size(); ++i)
          if (free_index[i] >= 0)
            du[i] = du_free[free_index[i]];
        if (du.lpNorm<Eigen::Infinity>() <= settings_.epsilon_r)
          break;

        // Backtracking on R from the largest step that keeps the reference mesh admissible;
        // every trial mesh re-solves the implicit step, warm-started from the current x.
        double          alpha = step_filter(r.u, du);
        Eigen::VectorXd u_trial, x_trial;
        double          trial_objective = std::numeric_limits<double>::infinity();
        for (; alpha > 1e-12; alpha *= 0.5)
          {
            ++r.line_search_trials;
            u_trial         = r.u + alpha * du;
            x_trial         = r.x;
            r.inner_iterations += solve_inner(u_trial, x_trial);
            trial_objective = objective(x_trial, u_trial);
            if (trial_objective <= current)
              break;
          }
        if (!(trial_objective <= current))
          break;  // no decrease along a descent direction: converged to round-off
        r.u       = u_trial;
        r.x       = x_trial;
        current   = trial_objective;
      }
    r.objective = current;
    r.v         = (r.x - transfer_.project(x_t, r.u)) / h;
    return r;
  }

  template class RitrSolver<1>;
  template class RitrSolver<2>;
  template class RitrSolver<3>;
} // namespace ritr
