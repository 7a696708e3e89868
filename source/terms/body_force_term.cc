#include <ritr/terms/body_force_term.h>
#include <ritr/terms/measure_weighted_cell.h>

namespace ritr
{
  template <int dim>
  void BodyForceTerm<dim>::begin_step(const StepContext<dim> &context)
  {
    gravity_ = context.gravity;
    weight_  = context.potential_weight();
    any_     = false;
    for (const double g : gravity_)
      any_ = any_ || g != 0.0;
  }

  template <int dim>
  Eigen::Matrix<double, dim, 1> BodyForceTerm<dim>::nodal_force_density(const unsigned int c) const
  {
    Eigen::Matrix<double, dim, 1> f;
    for (int k = 0; k < dim; ++k)
      f[k] = weight_ * materials_.of_cell(c).density / (dim + 1) * gravity_[k];
    return f;
  }

  template <int dim>
  double BodyForceTerm<dim>::value(const TermPoint &p) const
  {
    if (!any_)
      return 0.0;
    const auto &mesh = materials_.mesh();
    double      work = 0;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto &cell = mesh.cells[c];
        const auto  f    = nodal_force_density(c);
        double      s    = 0;
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            s += p.z[cell[a] * dim + k] * f[k];
        work += simplex_measure<dim, double>(cell_nodes<dim>(p.u, cell)) * s;
      }
    return -work;
  }

  template <int dim>
  void BodyForceTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    if (!any_)
      return;
    const auto &mesh = materials_.mesh();
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto  &cell    = mesh.cells[c];
        const double measure = simplex_measure<dim, double>(cell_nodes<dim>(p.u, cell));
        const auto   f       = nodal_force_density(c);
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            g[cell[a] * dim + k] -= measure * f[k];
      }
  }

  template <int dim>
  void BodyForceTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block, const bool coupling,
                                                     ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!any_)
      return;
    constexpr int                     n    = dim * (dim + 1);
    const auto                       &mesh = materials_.mesh();
    const Eigen::Matrix<double, n, n> q_xx = Eigen::Matrix<double, n, n>::Zero();
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto                 &cell = mesh.cells[c];
        const auto                  f    = nodal_force_density(c);
        Eigen::Matrix<double, n, 1> q_x;
        double                      q = 0;
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            {
              q_x[a * dim + k] = -f[k];
              q -= p.z[cell[a] * dim + k] * f[k];
            }
        add_measure_weighted_cell<dim>(c, cell, q, q_x, q_xx, cell_measure_derivatives<dim>(p.u, cell), block, coupling, d);
      }
  }

  template <int dim>
  void BodyForceTerm<dim>::add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!any_)
      return;
    const auto &mesh = materials_.mesh();
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto &cell = mesh.cells[c];
        const auto  f    = nodal_force_density(c);
        double      q    = 0;
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            q -= p.z[cell[a] * dim + k] * f[k];
        add_measure_weighted_gradient<dim>(cell, q, cell_measure_gradient<dim>(p.u, cell), d.gu);
      }
  }

  template class BodyForceTerm<1>;
  template class BodyForceTerm<2>;
  template class BodyForceTerm<3>;
} // namespace ritr
