#include <ritr/mesh/simplex_rules.h>

#include <deal.II/base/quadrature_lib.h>

namespace ritr
{
  namespace
  {
    template <int dim>
    SimplexQuadrature<dim> to_barycentric(const dealii::Quadrature<dim> &q)
    {
      SimplexQuadrature<dim> rule;
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
      check_rule(rule);
      return rule;
    }
  } // namespace

  template <int dim>
  SimplexQuadrature<dim> gauss_simplex_rule(const unsigned int n_points_1d)
  {
    if constexpr (dim == 1)
      return to_barycentric<dim>(dealii::QGauss<dim>(n_points_1d));
    else
      return to_barycentric<dim>(dealii::QGaussSimplex<dim>(n_points_1d));
  }

  template <int dim>
  SimplexQuadrature<dim> witherden_vincent_rule(const unsigned int n_points_1d)
  {
    if constexpr (dim == 1)
      return to_barycentric<dim>(dealii::QGauss<dim>(n_points_1d));
    else
      return to_barycentric<dim>(dealii::QWitherdenVincentSimplex<dim>(n_points_1d));
  }

  template SimplexQuadrature<1> gauss_simplex_rule<1>(unsigned int);
  template SimplexQuadrature<2> gauss_simplex_rule<2>(unsigned int);
  template SimplexQuadrature<3> gauss_simplex_rule<3>(unsigned int);
  template SimplexQuadrature<1> witherden_vincent_rule<1>(unsigned int);
  template SimplexQuadrature<2> witherden_vincent_rule<2>(unsigned int);
  template SimplexQuadrature<3> witherden_vincent_rule<3>(unsigned int);
} // namespace ritr
