#include <ritr/adaptivity/ritr_objective.h>

#include <ritr/common/wall_clock.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ritr
{
  template <int dim>
  RitrObjective<dim>::RitrObjective(const SimplexMesh<dim> &mesh, BulkEnergy<dim> &bulk,
                                    ContactPotential<dim> *contact, const SimplexQuadrature<dim> &quadrature,
                                    const InertiaForm inertia, const PredictorProjection projection)
    : mesh_(mesh)
    , bulk_(bulk)
    , mass_(mesh, std::vector<Material>(*std::max_element(mesh.cell_material.begin(), mesh.cell_material.end()) + 1,
                                        bulk.cell_material(0)))
    , contact_(contact)
    , transfer_(mesh.cells, quadrature)
    , inertia_(inertia)
    , projection_(projection)
  {
    // The transfer term rho x^T A_t y assumes one density (paper eq. 20).
    density_ = bulk.cell_material(0).density;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      if (bulk.cell_material(c).density != density_)
        throw std::invalid_argument("r-adaptivity needs one density for all bodies");
    CellEnergyWeights<dim> w;
    w.inertia   = 1;
    w.potential = 0;
    mass_.set_weights(w);
    mass_.set_predictor(Eigen::VectorXd::Zero(mesh.reference.size()));
  }

  template <int dim>
  void RitrObjective<dim>::begin_step(const StepContext<dim> &step)
  {
    const bool dynamic = step.dynamic;
    dynamic_           = dynamic;
    predictor_         = step.predictor();
    CellEnergyWeights<dim> w = step.cell_weights();
    w.corrected_inertia = !(projection_ == PredictorProjection::after_optimization && inertia_ == InertiaForm::uncorrected);
    bulk_.set_weights(w);
    // With the in-optimization projection the predictor enters through the transfer only.
    bulk_.set_predictor(uses_transfer() || !dynamic ? Eigen::VectorXd::Zero(predictor_.size()) : predictor_);
    if (dynamic)
      {
        ScopedTimer timer(transfer_seconds_);
        transfer_.set_old_mesh(step.u_start);
      }
  }

  template <int dim>
  void RitrObjective<dim>::set_candidate(const Eigen::VectorXd &u)
  {
    if (contact_)
      contact_->set_reference(u);
    if (!dynamic_)
      return;
    ScopedTimer timer(transfer_seconds_);
    transfer_.set_candidate(u);
    if (adds_projected_predictor())
      projected_predictor_ = transfer_.project(predictor_);
  }

  template <int dim>
  Eigen::VectorXd RitrObjective<dim>::linear_term() const
  {
    if (!uses_transfer())
      return {};
    ScopedTimer timer(transfer_seconds_);
    return -density_ * transfer_.gradient_x(predictor_);
  }

  template <int dim>
  double RitrObjective<dim>::value(const Eigen::VectorXd &z, const Eigen::VectorXd &u) const
  {
    const Eigen::VectorXd x = z.head(u.size());
    double                r = bulk_.value(x, u);
    if (!std::isfinite(r))
      return std::numeric_limits<double>::infinity();
    if (uses_transfer())
      {
        ScopedTimer timer(transfer_seconds_);
        r -= density_ * transfer_.value(x, predictor_);
        if (adds_projected_predictor())
          r += 0.5 * density_ * transfer_.value(projected_predictor_, predictor_);  // 1/2 rho pi^T Mbar pi
      }
    if (contact_)
      r += contact_->value(z, contact_->candidates_at(z));
    if (kappa_w_ > 0)
      r += reference_measure_barrier(mesh_, u, w_hat_, kappa_w_);
    return r;
  }

  template <int dim>
  typename RitrObjective<dim>::Derivatives RitrObjective<dim>::derivatives(const Eigen::VectorXd &z,
                                                                           const Eigen::VectorXd &u,
                                                                           const ReferenceBlock block,
                                                                           const bool coupling) const
  {
    const Eigen::VectorXd x         = z.head(u.size());
    const bool following = block == ReferenceBlock::following;
    Derivatives           d;
    {
      typename BulkEnergy<dim>::JointDerivatives joint;
      bulk_.joint_derivatives(x, u, block, joint);
      d.gu  = std::move(joint.gu);
      d.huu = std::move(joint.huu);
      if (coupling)
        {
          d.gx = Eigen::VectorXd::Zero(z.size());
          d.gx.head(x.size()) = joint.gx;
          d.hxx = std::move(joint.hxx);
          d.hxu = std::move(joint.hxu);
        }
    }
    if (uses_transfer())
      {
        ScopedTimer timer(transfer_seconds_);
        d.gu -= density_ * transfer_.gradient_u(x, predictor_);
        if (following)
          transfer_.add_hessian_following(x, predictor_, -density_, false, d.huu);
        else
          transfer_.add_hessian_u(x, predictor_, -density_, false, d.huu);
        if (coupling)
          {
            d.gx.head(x.size()) -= density_ * transfer_.gradient_x(predictor_);
            transfer_.add_hessian_xu(x, predictor_, -density_, d.hxu);
          }
        if (adds_projected_predictor())
          {
            // 1/2 rho pi^T Mbar pi = max_p g(p, u), g = rho p^T A y - 1/2 p^T M p: by the
            // envelope theorem its gradient is g_u at p = pi, and its Hessian is
            // g_uu + g_up M^-1 g_pu. The response part is dense and is only formed with the
            // coupling blocks (full and filtered outer Hessians); the truncated one keeps g_uu.
            typename BulkEnergy<dim>::JointDerivatives kinetic;
            mass_.joint_derivatives(projected_predictor_, u, ReferenceBlock::exact, kinetic);
            d.gu += density_ * transfer_.gradient_u(projected_predictor_, predictor_) - kinetic.gu;
            transfer_.add_hessian_u(projected_predictor_, predictor_, density_, false, d.huu);
            for (const auto &t : kinetic.huu)
              d.huu.emplace_back(t.row(), t.col(), -t.value());
            if (coupling)
              add_projection_response(kinetic, u.size(), d.huu);
          }
      }
    if (contact_)
      {
        const CollisionCandidates candidates = contact_->candidates_at(z);
        typename ContactPotential<dim>::ReferenceDerivatives rd;
        contact_->reference_derivatives(z, candidates, rd);
        d.gu += rd.gu;
        d.huu.insert(d.huu.end(), rd.huu.begin(), rd.huu.end());
        if (following)
          {
            // H_xu + H_ux + H_xx restricted to the body's nodes (x follows u there).
            const Eigen::Index n_u = u.size();
            for (const auto &t : rd.hxu)
              if (t.row() < n_u)
                {
                  d.huu.emplace_back(t.row(), t.col(), t.value());
                  d.huu.emplace_back(t.col(), t.row(), t.value());
                }
            Triplets hxx;
            contact_->add_hessian(z, candidates, hxx, true);
            for (const auto &t : hxx)
              if (t.row() < n_u && t.col() < n_u)
                d.huu.push_back(t);
          }
        if (coupling)
          {
            contact_->add_gradient(z, candidates, d.gx);
            contact_->add_hessian(z, candidates, d.hxx, true);
            d.hxu.insert(d.hxu.end(), rd.hxu.begin(), rd.hxu.end());
          }
      }
    if (kappa_w_ > 0)
      reference_measure_barrier(mesh_, u, w_hat_, kappa_w_, &d.gu, &d.huu, true);
    return d;
  }

  template <int dim>
  void RitrObjective<dim>::add_projection_response(const typename BulkEnergy<dim>::JointDerivatives &kinetic,
                                                   const Eigen::Index n_u, Triplets &huu) const
  {
    Triplets g_pu_triplets;
    transfer_.add_hessian_xu(projected_predictor_, predictor_, density_, g_pu_triplets);
    for (const auto &t : kinetic.hxu)
      g_pu_triplets.emplace_back(t.row(), t.col(), -t.value());
    Eigen::SparseMatrix<double> g_pu(n_u, n_u), mass(n_u, n_u);
    g_pu.setFromTriplets(g_pu_triplets.begin(), g_pu_triplets.end());
    mass.setFromTriplets(kinetic.hxx.begin(), kinetic.hxx.end());
    const Eigen::MatrixXd dense_g_pu = Eigen::MatrixXd(g_pu);
    const Eigen::MatrixXd response   = dense_g_pu.transpose() * Eigen::MatrixXd(mass).ldlt().solve(dense_g_pu);
    for (Eigen::Index j = 0; j < n_u; ++j)
      for (Eigen::Index i = 0; i < n_u; ++i)
        if (response(i, j) != 0.0)
          huu.emplace_back(i, j, response(i, j));
  }

  template <int dim>
  Eigen::VectorXd RitrObjective<dim>::project(const Eigen::VectorXd &y, const Eigen::VectorXd &u)
  {
    ScopedTimer timer(transfer_seconds_);
    return transfer_.project(y, u);
  }

  template class RitrObjective<1>;
  template class RitrObjective<2>;
  template class RitrObjective<3>;
} // namespace ritr
