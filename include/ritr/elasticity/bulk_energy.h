#pragma once
// Assembly of the cell terms (inertia, elasticity, gravity; see cell_energy.h) over a mesh.
// Values, gradients and projected Hessians w.r.t. the deformed positions x use a fast path
// (the strain energy's derivatives in F, mapped by the constant P1 shape gradients); the
// joint derivatives w.r.t. (x, u) use automatic differentiation of the same kernel.
#include <ritr/elasticity/cell_energy.h>
#include <ritr/mesh/simplex_mesh.h>

#include <Eigen/Sparse>

#include <vector>

namespace ritr
{
  using Triplets = std::vector<Eigen::Triplet<double>>;

  // The u-u Hessian block of an element for r-adaptivity:
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

  template <int dim>
  class BulkEnergy
  {
  public:
    // `materials[id]` is the material of cells with material id `id`.
    BulkEnergy(const SimplexMesh<dim> &mesh, const std::vector<Material> &materials);

    void set_weights(const CellEnergyWeights<dim> &weights) { weights_ = weights; }
    const CellEnergyWeights<dim> &weights() const { return weights_; }
    // Inertia target, on the same mesh (fixed-mesh mode: the predictor x^t + h v^t).
    void set_predictor(const Eigen::VectorXd &x_pred) { x_pred_ = x_pred; }

    // +infinity when an element is inverted (neo-Hookean).
    double value(const Eigen::VectorXd &x, const Eigen::VectorXd &u) const;
    // Adds the gradient w.r.t. x to g (size n_nodes * dim).
    void add_gradient(const Eigen::VectorXd &x, const Eigen::VectorXd &u, Eigen::VectorXd &g) const;
    // Appends the Hessian w.r.t. x; `project` makes each element block positive semi-definite.
    void add_hessian(const Eigen::VectorXd &x, const Eigen::VectorXd &u, bool project,
                     Triplets &hessian) const;

    // Joint derivatives w.r.t. (x, u): gradients g_x, g_u and the Hessian blocks
    // H_xx, H_xu, H_uu (appended as triplets); `block` says what goes into H_uu per element.
    struct JointDerivatives
    {
      Eigen::VectorXd gx, gu;
      Triplets        hxx, hxu, huu;
    };
    void joint_derivatives(const Eigen::VectorXd &x, const Eigen::VectorXd &u, ReferenceBlock block,
                           JointDerivatives &out) const;

    const SimplexMesh<dim> &mesh() const { return mesh_; }
    const Material &cell_material(unsigned int c) const { return materials_[mesh_.cell_material[c]]; }

    // Lumped (row-sum) nodal masses at reference positions u.
    Eigen::VectorXd nodal_masses(const Eigen::VectorXd &u) const;

  private:
    const SimplexMesh<dim> &mesh_;
    std::vector<Material>   materials_;
    CellEnergyWeights<dim>  weights_;
    Eigen::VectorXd         x_pred_;
  };
} // namespace ritr
