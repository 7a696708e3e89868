#pragma once
// The IPC barrier kappa B(z, u): B = sum_k w_k(u) m_k b(d_k(z)) over the candidates' pairs
// within dhat, weighted by the reference boundary measure of each constraint's point (the
// spatially continuous form), with IPC's convention that the potential carries kappa B.
// The stiffness is set by the implicit step at the start of a time step (IPC's rule, adapted
// while the first solve runs) and is then fixed for the step. Its step bound is CCD.
#include <ritr/terms/energy_term.h>

namespace ritr
{
  template <int dim>
  class ContactBarrierTerm : public EnergyTerm<dim>
  {
  public:
    explicit ContactBarrierTerm(const CollisionMesh<dim> &collisions) : collisions_(collisions) {}

    void   set_stiffness(double kappa) { kappa_ = kappa; }
    double stiffness() const { return kappa_; }
    // dB/dz without the stiffness (IPC's stiffness rule compares it with the other terms).
    Eigen::VectorXd unscaled_gradient(const Eigen::VectorXd &z, const CollisionCandidates &candidates) const;

    bool   is_contact() const override { return true; }
    const char *name() const override { return "contact barrier"; }
    double value(const TermPoint &p) const override;
    void   add_gradient(const TermPoint &p, Eigen::VectorXd &g) const override;
    void   add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const override;
    void   add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const override;
    void   add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                     ReferenceDerivativeAssembly<dim> &d) const override;
    double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz, const CollisionCandidates &along) const override
    {
      return collisions_.max_step(z, dz, along);
    }

  private:
    const CollisionMesh<dim> &collisions_;
    double                    kappa_ = 0;
  };

  // The x-dependence of a contact term that the outer solve adds on top of its weights'
  // derivatives: the projected z-Hessian `hessian` (state numbering) goes into H_zz with the
  // coupling blocks, and with ReferenceBlock::following its body part, with the mixed blocks
  // `hxu` on body rows in both orders, into H_uu (x follows u there).
  void add_contact_state_blocks(Eigen::Index n_body, const Triplets &hessian, const Triplets &hxu, ReferenceBlock block,
                                bool coupling, Triplets &huu, Triplets &hxx, Triplets &hxu_out);
} // namespace ritr
