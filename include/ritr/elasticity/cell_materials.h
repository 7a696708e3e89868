#pragma once
// The material of every cell of a mesh (one per material id) and what follows from the
// materials alone: lumped nodal masses.
#include <ritr/elasticity/material.h>
#include <ritr/mesh/simplex_mesh.h>

#include <vector>

namespace ritr
{
  template <int dim>
  class CellMaterials
  {
  public:
    // `materials[id]` is the material of the cells with material id `id`; throws
    // std::runtime_error if a cell's id has none. The mesh must outlive this.
    CellMaterials(const SimplexMesh<dim> &mesh, std::vector<Material> materials);

    const SimplexMesh<dim> &mesh() const { return mesh_; }
    const Material         &of_cell(const unsigned int c) const { return materials_[mesh_.cell_material[c]]; }
    const std::vector<Material> &materials() const { return materials_; }

    // Lumped (row-sum) nodal masses at reference positions u.
    Eigen::VectorXd nodal_masses(const Eigen::VectorXd &u) const;

  private:
    const SimplexMesh<dim> &mesh_;
    std::vector<Material>   materials_;
  };
} // namespace ritr
