#include <ritr/elasticity/cell_materials.h>

#include <stdexcept>
#include <string>

namespace ritr
{
  template <int dim>
  CellMaterials<dim>::CellMaterials(const SimplexMesh<dim> &mesh, std::vector<Material> materials)
    : mesh_(mesh)
    , materials_(std::move(materials))
  {
    for (const unsigned int id : mesh.cell_material)
      if (id >= materials_.size())
        throw std::runtime_error("cells have material id " + std::to_string(id) +
                                 " but no material with that id is defined");
  }

  template <int dim>
  Eigen::VectorXd CellMaterials<dim>::nodal_masses(const Eigen::VectorXd &u) const
  {
    Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh_.n_nodes());
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      {
        const double share =
          of_cell(c).density * simplex_measure<dim, double>(cell_nodes<dim>(u, mesh_.cells[c])) / (dim + 1);
        for (const unsigned int node : mesh_.cells[c])
          m[node] += share;
      }
    return m;
  }

  template class CellMaterials<1>;
  template class CellMaterials<2>;
  template class CellMaterials<3>;
} // namespace ritr
