#pragma once
// The simulation mesh as the solvers see it: reference node positions u (which r-adaptivity
// moves), fixed simplex connectivity, material ids and the oriented boundary facets.
//
// Positions are stored as flat vectors (node-major: entry i*dim + k) because the solvers
// treat u and the deformed positions x as vectors of unknowns. deal.II builds and numbers
// the mesh (see mesh_builder.h); everything downstream works on this structure.
#include <ritr/common/small_matrix.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ritr
{
  template <int dim>
  using Vec = Eigen::Matrix<double, dim, 1>;

  template <int dim>
  struct SimplexMesh
  {
    static constexpr int nodes_per_cell = dim + 1;
    using Cell  = std::array<unsigned int, dim + 1>;
    using Facet = std::array<unsigned int, dim>;

    Eigen::VectorXd       reference;      // u, size n_nodes * dim
    std::vector<Cell>     cells;          // positively oriented in the reference configuration
    std::vector<unsigned> cell_material;  // material id per cell
    std::vector<Facet>    boundary_facets;  // oriented with outward normal (2D: CCW boundary)
    std::vector<unsigned> boundary_ids;     // boundary id per facet
    std::vector<unsigned> node_body;        // connected component (body) of each node
    std::vector<unsigned> node_part;        // index of the BodyDescription it was built from

    unsigned int n_nodes() const { return reference.size() / dim; }
    unsigned int n_cells() const { return cells.size(); }
    unsigned int n_bodies() const;

    Vec<dim> reference_node(const unsigned int i) const { return reference.template segment<dim>(i * dim); }
  };

  // Node positions of a cell from a flat position vector, as the nested arrays that the
  // templated element kernels take.
  template <int dim>
  std::array<std::array<double, dim>, dim + 1> cell_nodes(const Eigen::VectorXd &positions,
                                                          const std::array<unsigned int, dim + 1> &cell)
  {
    std::array<std::array<double, dim>, dim + 1> m;
    for (int a = 0; a <= dim; ++a)
      for (int k = 0; k < dim; ++k)
        m[a][k] = positions[cell[a] * dim + k];
    return m;
  }

  // Smallest signed cell measure of the mesh evaluated at `positions` (reference or deformed),
  // normalised per cell by the reference measure when `relative` is true.
  template <int dim>
  double min_cell_measure(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &positions,
                          bool relative);
} // namespace ritr
