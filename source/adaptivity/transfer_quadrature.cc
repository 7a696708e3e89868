#include <ritr/adaptivity/transfer_quadrature.h>

#include <deal.II/base/quadrature_lib.h>

namespace ritr
{
  template <int dim>
  transfer::SimplexQuadrature<dim> witherden_vincent_rule(const unsigned int n_points_1d)
  {
    const dealii::Quadrature<dim> q = dim == 1 ? dealii::Quadrature<dim>(dealii::QGauss<dim>(n_points_1d)) :
                                                 dealii::Quadrature<dim>(dealii::QWitherdenVincentSimplex<dim>(n_points_1d));
    transfer::SimplexQuadrature<dim> rule;
    for (unsigned int p = 0; p < q.size(); ++p)
      {
        std::array<double, dim + 1> lambda;
        lambda[0] = 1.0;
        for (int k = 0; k < dim; ++k)
          {
            lambda[k + 1] = q.point(p)[k];
            lambda[0] -= q.point(p)[k];
          }
        rule.points.push_back(lambda);
        rule.weights.push_back(q.weight(p));
      }
    transfer::check_rule(rule);
    return rule;
  }

  template transfer::SimplexQuadrature<1> witherden_vincent_rule<1>(unsigned int);
  template transfer::SimplexQuadrature<2> witherden_vincent_rule<2>(unsigned int);
  template transfer::SimplexQuadrature<3> witherden_vincent_rule<3>(unsigned int);
} // namespace ritr
