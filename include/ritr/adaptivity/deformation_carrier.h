#pragma once
// The state at a trial reference mesh u + du, predicted without a solve by carrying the
// current deformation over: a moved node takes the deformed position of the material point it
// moves to, the current piecewise-linear map u -> x evaluated in the cell of the node's star
// that holds the point (outside its star, extended linearly from the cell it is nearest to
// lying in). Moving reference nodes leaves the deformed shape as it was, so the inner solve
// starts where only the reference change's effect on the energy remains to be solved; the
// first-order outer solve uses it in place of the implicit-function response.
#include <ritr/mesh/simplex_mesh.h>

#include <Eigen/Core>

#include <vector>

namespace ritr
{
  template <int dim>
  class DeformationCarrier
  {
  public:
    explicit DeformationCarrier(const SimplexMesh<dim> &mesh);

    // The change of the body's deformed positions x (mesh numbering) when the reference moves
    // from u by du.
    Eigen::VectorXd carried(const Eigen::VectorXd &x, const Eigen::VectorXd &u, const Eigen::VectorXd &du) const;

  private:
    const SimplexMesh<dim>        &mesh_;
    std::vector<std::vector<int>> star_;  // the cells around each node
  };
} // namespace ritr
