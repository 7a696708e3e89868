#pragma once
// One term of the incremental potential E(x, u) of a step (paper eq. 6) or of the r-ITR
// objective R(x, u) = E(x, u) + C(u) (eq. 14): inertia, elasticity, body forces, the contact
// barrier, lagged friction, the reference measure barrier. Every term gives its value and its
// derivatives in the state z = [body node positions x, obstacle vertices] for the inner solve
// and in the body's reference positions u for the outer one; a TermSum (term_sum.h) adds
// them up for both, in the spirit of PolyFEM's forms and IPC Toolkit's potentials.
//
// A term takes the step's fixed data in begin_step() and the mesh of the evaluations that
// follow in set_reference(); everything else is passed in. An inadmissible state (an
// inverted element, touching primitives) has the value +infinity: the line searches need the
// value anyway, so validity is not a second pass over the mesh.
#include <ritr/common/matrix_assembly.h>
#include <ritr/contact/collision_mesh.h>
#include <ritr/terms/step_context.h>

namespace ritr
{
  // The u-u block of the outer Hessian:
  //  - exact: d2/du2 at fixed x;
  //  - following: d2/du2 along moves that carry x with u (x - u fixed), i.e.
  //    H_uu + H_ux + H_xu + H_xx. Moving a reference node while its deformed position stays
  //    put rewrites the deformation field, so at fixed x the curvature in u is dominated by
  //    that rewrite; with x following it measures how the mesh carries the same motion.
  //    Summed over elements (not projected per element: the element blocks cancel), it
  //    equals the reduced Hessian plus K^T H_xx^-1 K with K = H_xx + H_xu, so it bounds the
  //    reduced Hessian from above where H_xx is positive definite.
  enum class ReferenceBlock
  {
    exact,
    following
  };

  // Where a term is evaluated: the state, the reference mesh last set, and the collision
  // candidates the caller built for this state (empty without contact).
  struct TermPoint
  {
    const Eigen::VectorXd     &z;
    const Eigen::VectorXd     &u;
    const CollisionCandidates &candidates;

    // The body's entries of the state (its first u.size() entries).
    auto x() const { return z.head(u.size()); }
  };

  // The outer solve's derivatives under assembly: g_u and H_uu in reference numbering and,
  // with the coupling blocks, g_z and H_zz in state numbering and H_zu (rows: state,
  // columns: reference).
  template <int dim>
  struct ReferenceDerivativeAssembly
  {
    ReferenceDerivativeAssembly(const std::vector<typename MatrixAssembly<dim>::Cell> &cells)
      : huu(cells), hxx(cells), hxu(cells)
    {}
    Eigen::VectorXd     gu, gx;
    MatrixAssembly<dim> huu, hxx, hxu;
  };

  template <int dim>
  class EnergyTerm
  {
  public:
    virtual ~EnergyTerm() = default;

    // What the term is, for the outputs (summary.json splits the final energy by term).
    virtual const char *name() const = 0;

    // A term of the reference mesh alone (the measure barrier) is a constant of the inner
    // solve over z: it belongs to R, not to E.
    virtual bool depends_on_state() const { return true; }
    // Barrier and friction: the contact force and IPC's stiffness rule take them apart.
    virtual bool is_contact() const { return false; }

    virtual void begin_step(const StepContext<dim> &context) { (void)context; }
    // The reference mesh of the evaluations that follow (cell measures, contact weights, the
    // transfer's quadrature located in the start-of-step mesh).
    virtual void set_reference(const Eigen::VectorXd &u) { (void)u; }

    virtual double value(const TermPoint &p) const = 0;
    // d/dz added to g (state numbering).
    virtual void add_gradient(const TermPoint &p, Eigen::VectorXd &g) const = 0;
    // d2/dz2; with `project` every stencil's block is projected onto the PSD cone.
    virtual void add_hessian(const TermPoint &p, bool project, MatrixAssembly<dim> &h) const = 0;
    // A term whose every stencil is PSD in z (inertia, linear terms) has nothing to project.
    virtual bool convex_in_state() const { return false; }
    // Both Hessians the trust-region Newton uses, in one pass: the exact one into h and the
    // projection's changes into h's change layer (matrix_assembly.h), only on the stencils the
    // projection alters. The default assembles the term twice more; terms override it to
    // compute each stencil once.
    virtual void add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const
    {
      const std::size_t first = h.triplets().size();
      add_hessian(p, false, h);
      if (convex_in_state())
        return;
      MatrixAssembly<dim> plain(h.cells()), projected(h.cells());
      add_hessian(p, false, plain);
      add_hessian(p, true, projected);
      h.change_by(plain, projected, first);
    }
    // g_u and H_uu (per `block`); with `coupling` also g_z, H_zz and H_zu. H_zz there is the
    // matrix the reduced Hessian eliminates: exact for cell terms, projected for contact.
    virtual void add_reference_derivatives(const TermPoint &p, ReferenceBlock block, bool coupling,
                                           ReferenceDerivativeAssembly<dim> &d) const = 0;
    // g_u alone, added to d.gu: all that a first-order outer solve needs. The default takes it
    // from add_reference_derivatives (and leaves H_uu in d, which the caller discards); terms
    // whose second derivatives cost much more than their gradient override it.
    virtual void add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const
    {
      add_reference_derivatives(p, ReferenceBlock::exact, false, d);
    }
    // Largest fraction of the step dz from z that keeps the state admissible (contact: CCD
    // over `along`, the pairs whose boxes swept along the step come within dhat, of all
    // processes: CollisionMesh::candidates_along).
    virtual double max_step(const Eigen::VectorXd &z, const Eigen::VectorXd &dz, const CollisionCandidates &along) const
    {
      (void)z;
      (void)dz;
      (void)along;
      return 1.0;
    }
  };
} // namespace ritr
