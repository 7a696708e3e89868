#include <ritr/adaptivity/deformation_carrier.h>

#include <Eigen/Dense>

#include <limits>

namespace ritr
{
  template <int dim>
  DeformationCarrier<dim>::DeformationCarrier(const SimplexMesh<dim> &mesh)
    : mesh_(mesh)
    , star_(mesh.n_nodes())
  {
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      for (const unsigned int n : mesh.cells[c])
        star_[n].push_back(c);
  }

  template <int dim>
  Eigen::VectorXd DeformationCarrier<dim>::carried(const Eigen::VectorXd &x, const Eigen::VectorXd &u,
                                                   const Eigen::VectorXd &du) const
  {
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(u.size());
    for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
      {
        const Vec<dim> step = du.template segment<dim>(i * dim);
        if (step.isZero(0.0))
          continue;
        const Vec<dim> target = u.template segment<dim>(i * dim) + step;
        // The cell of the star whose smallest barycentric coordinate of the target is largest:
        // the one holding it, or the nearest to holding it.
        double                         best = -std::numeric_limits<double>::infinity();
        Eigen::Matrix<double, dim + 1, 1> best_lambda;
        int                            best_cell = -1;
        for (const int c : star_[i])
          {
            const auto                     &cell = mesh_.cells[c];
            Eigen::Matrix<double, dim, dim> edges;
            for (int a = 1; a <= dim; ++a)
              edges.col(a - 1) = u.template segment<dim>(cell[a] * dim) - u.template segment<dim>(cell[0] * dim);
            const Vec<dim> local = edges.partialPivLu().solve(target - u.template segment<dim>(cell[0] * dim));
            Eigen::Matrix<double, dim + 1, 1> lambda;
            lambda[0]                   = 1 - local.sum();
            lambda.template tail<dim>() = local;
            if (lambda.minCoeff() > best)
              {
                best        = lambda.minCoeff();
                best_lambda = lambda;
                best_cell   = c;
              }
          }
        if (best_cell < 0)
          continue;
        Vec<dim> moved = Vec<dim>::Zero();
        for (int a = 0; a <= dim; ++a)
          moved += best_lambda[a] * x.template segment<dim>(mesh_.cells[best_cell][a] * dim);
        dx.template segment<dim>(i * dim) = moved - x.template segment<dim>(i * dim);
      }
    return dx;
  }

  template class DeformationCarrier<1>;
  template class DeformationCarrier<2>;
  template class DeformationCarrier<3>;
} // namespace ritr
