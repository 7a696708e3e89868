#include <ritr/common/wall_clock.h>
#include <ritr/terms/transferred_inertia_term.h>

#include <Eigen/Dense>

#include <stdexcept>

namespace ritr
{
  template <int dim>
  TransferredInertiaTerm<dim>::TransferredInertiaTerm(const CellMaterials<dim>     &materials,
                                                      const SimplexQuadrature<dim> &quadrature, const InertiaForm form,
                                                      const transfer::TransferIntegration integration)
    : mass_(materials, InertiaTerm<dim>::Predictor::none, InertiaForm::corrected)
    , transfer_(materials.mesh().cells, quadrature, integration)
    , form_(form)
  {
    // The transfer term rho x^T A_t y assumes one density (paper eq. 20).
    density_ = materials.of_cell(0).density;
    for (unsigned int c = 0; c < materials.mesh().n_cells(); ++c)
      if (materials.of_cell(c).density != density_)
        throw std::invalid_argument("r-adaptivity needs one density for all bodies");
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::begin_step(const StepContext<dim> &context)
  {
    mass_.begin_step(context);
    active_    = context.dynamic;
    predictor_ = context.predictor();
    if (!active_)
      return;
    ScopedTimer timer(seconds_);
    transfer_.set_old_mesh(context.u_start);
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::set_reference(const Eigen::VectorXd &u)
  {
    if (!active_)
      return;
    ScopedTimer timer(seconds_);
    transfer_.set_candidate(u);
    linear_ = -density_ * transfer_.gradient_x(predictor_);
    if (adds_projected_predictor())
      {
        projected_ = transfer_.project(predictor_);
        constant_  = 0.5 * density_ * transfer_.value(projected_, predictor_);  // 1/2 rho pi^T Mbar pi
      }
  }

  template <int dim>
  double TransferredInertiaTerm<dim>::value(const TermPoint &p) const
  {
    if (!active_)
      return 0.0;
    double k = mass_.value(p) + linear_.dot(p.x());
    if (adds_projected_predictor())
      k += constant_;
    return k;
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    if (!active_)
      return;
    mass_.add_gradient(p, g);
    g.head(linear_.size()) += linear_;
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    if (active_)
      mass_.add_hessian(p, project, h);  // the transfer part is linear in x
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block,
                                                              const bool coupling, ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!active_)
      return;
    mass_.add_reference_derivatives(p, block, coupling, d);
    ScopedTimer           timer(seconds_);
    const Eigen::VectorXd x = p.x();
    transfer_.add_reference_derivatives(x, predictor_, -density_, block == ReferenceBlock::following, d.gu,
                                        d.huu.triplets(), coupling ? &d.hxu.triplets() : nullptr);
    if (coupling)
      d.gx.head(x.size()) += linear_;
    if (!adds_projected_predictor())
      return;
    // 1/2 rho pi^T Mbar pi = max_p g(p, u), g = rho p^T A y - 1/2 p^T M p: by the envelope
    // theorem its gradient is g_u at p = pi, and its Hessian is g_uu + g_up M^-1 g_pu. The
    // response part is dense and is only formed with the coupling blocks (full and filtered
    // outer Hessians); the truncated one keeps g_uu.
    const CollisionCandidates        none;
    ReferenceDerivativeAssembly<dim> kinetic(transfer_.cells());
    kinetic.gu = Eigen::VectorXd::Zero(x.size());
    kinetic.gx = Eigen::VectorXd::Zero(x.size());
    kinetic.huu.use_cell_blocks();
    kinetic.hxx.use_cell_blocks();
    kinetic.hxu.use_cell_blocks();
    mass_.add_reference_derivatives(TermPoint{projected_, p.u, none}, ReferenceBlock::exact, true, kinetic);
    d.gu += density_ * transfer_.gradient_u(projected_, predictor_) - kinetic.gu;
    transfer_.add_hessian_u(projected_, predictor_, density_, false, d.huu.triplets());
    for (const auto &t : kinetic.huu.to_triplets())
      d.huu.triplets().emplace_back(t.row(), t.col(), -t.value());
    if (coupling)
      add_projection_response(kinetic, d.huu.triplets());
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!active_)
      return;
    if (adds_projected_predictor())
      {
        add_reference_derivatives(p, ReferenceBlock::exact, false, d);  // the ablation: no fast path
        return;
      }
    mass_.add_reference_gradient(p, d);
    ScopedTimer timer(seconds_);
    d.gu -= density_ * transfer_.gradient_u(p.x(), predictor_);
  }

  template <int dim>
  void TransferredInertiaTerm<dim>::add_projection_response(const ReferenceDerivativeAssembly<dim> &kinetic,
                                                            Triplets                               &huu) const
  {
    const Eigen::Index n_u = projected_.size();
    Triplets           g_pu_triplets;
    transfer_.add_hessian_xu(projected_, predictor_, density_, g_pu_triplets);
    for (const auto &t : kinetic.hxu.to_triplets())
      g_pu_triplets.emplace_back(t.row(), t.col(), -t.value());
    const Triplets              mass_triplets = kinetic.hxx.to_triplets();
    Eigen::SparseMatrix<double> g_pu(n_u, n_u), mass(n_u, n_u);
    g_pu.setFromTriplets(g_pu_triplets.begin(), g_pu_triplets.end());
    mass.setFromTriplets(mass_triplets.begin(), mass_triplets.end());
    const Eigen::MatrixXd dense_g_pu = Eigen::MatrixXd(g_pu);
    const Eigen::MatrixXd response   = dense_g_pu.transpose() * Eigen::MatrixXd(mass).ldlt().solve(dense_g_pu);
    for (Eigen::Index j = 0; j < n_u; ++j)
      for (Eigen::Index i = 0; i < n_u; ++i)
        if (response(i, j) != 0.0)
          huu.emplace_back(i, j, response(i, j));
  }

  template class TransferredInertiaTerm<1>;
  template class TransferredInertiaTerm<2>;
  template class TransferredInertiaTerm<3>;
} // namespace ritr
