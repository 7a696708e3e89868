#pragma once
// Per-cell measures reported in the outputs and checked as invariants.
#include <ritr/mesh/simplex_mesh.h>

#include <vector>

namespace ritr
{
  // Scalar strain |F^T F - I|_F / 2 of each cell of the deformation u -> x.
  template <int dim>
  std::vector<double> cell_strains(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                                   const Eigen::VectorXd &u);

  // Shape quality of each cell at positions p, in (0, 1] (1 for the regular simplex):
  // dim * (dim! measure)^(2/dim) / (sum of squared edge lengths) scaled to 1 at the
  // regular simplex; 1 for line segments.
  template <int dim>
  std::vector<double> cell_qualities(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &p);

  // Smallest deformed Jacobian det F = measure(x) / measure(u) over the cells.
  template <int dim>
  double min_deformed_jacobian(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                               const Eigen::VectorXd &u);

  // Diagonal of the axis-aligned bounding box of nodal positions p (dim values per node): the
  // length scale that solver tolerances are relative to.
  template <int dim>
  double bounding_box_diagonal(const Eigen::VectorXd &p);

  // Contact pressure at every node of the deformed mesh x (0 off the boundary): the normal
  // component of the nodal contact force (positive when it pushes into the body) divided by
  // the node's share of the deformed boundary measure, 1/dim of each facet around it. The
  // normal is the measure-weighted mean of those facets' outward normals. 1D rods have a unit
  // cross-section and a force along the rod: the pressure is |f|.
  template <int dim>
  Eigen::VectorXd nodal_contact_pressures(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                                          const Eigen::VectorXd &contact_forces);

  // Peak resident set size of this process in bytes.
  long peak_rss_bytes();
} // namespace ritr
