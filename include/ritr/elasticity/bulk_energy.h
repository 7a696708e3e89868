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
    // H_xx, H_xu, H_uu (appended as triplets). With `project_uu` each element's u-u block
    // is projected to be positive semi-definite (the truncated Hessian of paper eq. 23).
    struct JointDerivatives
    {
      Eigen::VectorXd gx, gu;
      Triplets        hxx, hxu, huu;
    };
    void joint_derivatives(const Eigen::VectorXd &x, const Eigen::VectorXd &u, bool project_uu,
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
