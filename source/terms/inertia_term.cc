#include <ritr/elasticity/cell_energy.h>
#include <ritr/terms/inertia_term.h>
#include <ritr/terms/measure_weighted_cell.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace ritr
{
  namespace
  {
    constexpr std::size_t grain = 256;

    // The cell's kinetic part per unit measure and density, sum_ab m_ab (1/2 x_a.x_b - x_a.p_b
    // [+ 1/2 p_a.p_b]), and its gradient in the cell's positions.
    template <int dim>
    double kinetic_density(const Eigen::VectorXd &z, const Eigen::VectorXd &predictor,
                           const std::array<unsigned int, dim + 1> &cell, const bool uncorrected)
    {
      const auto &mass    = unit_mass_coefficients<dim>();
      double      kinetic = 0;
      for (int a = 0; a <= dim; ++a)
        for (int b = 0; b <= dim; ++b)
          for (int k = 0; k < dim; ++k)
            {
              const double xa = z[cell[a] * dim + k], xb = z[cell[b] * dim + k];
              const double pa = predictor[cell[a] * dim + k], pb = predictor[cell[b] * dim + k];
              double       term = 0.5 * xa * xb - xa * pb;
              if (uncorrected)
                term += 0.5 * pa * pb;
              kinetic += mass[a][b] * term;
            }
      return kinetic;
    }
  } // namespace

  template <int dim>
  InertiaTerm<dim>::InertiaTerm(const CellMaterials<dim> &materials, const Predictor predictor, const InertiaForm form)
    : materials_(materials)
    , predictor_kind_(predictor)
    , form_(form)
  {}

  template <int dim>
  void InertiaTerm<dim>::begin_step(const StepContext<dim> &context)
  {
    active_    = context.dynamic;
    predictor_ = predictor_kind_ == Predictor::nodal ? context.predictor() : Eigen::VectorXd::Zero(context.u_start.size());
  }

  template <int dim>
  double InertiaTerm<dim>::value(const TermPoint &p) const
  {
    if (!active_)
      return 0.0;
    const auto &mesh        = materials_.mesh();
    const bool  uncorrected = form_ == InertiaForm::uncorrected && predictor_kind_ == Predictor::nodal;
    return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), 0.0,
      [&](const tbb::blocked_range<std::size_t> &range, double sum) {
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            const auto  &cell    = mesh.cells[c];
            const double measure = simplex_measure<dim, double>(cell_nodes<dim>(p.u, cell));
            sum += materials_.of_cell(c).density * measure * kinetic_density<dim>(p.z, predictor_, cell, uncorrected);
          }
        return sum;
      },
      std::plus<double>());
  }

  template <int dim>
  void InertiaTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    if (!active_)
      return;
    const auto &mesh = materials_.mesh();
    const auto &mass = unit_mass_coefficients<dim>();
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto  &cell  = mesh.cells[c];
        const double scale = materials_.of_cell(c).density * simplex_measure<dim, double>(cell_nodes<dim>(p.u, cell));
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            {
              double d = 0;
              for (int b = 0; b <= dim; ++b)
                d += scale * mass[a][b] * (p.z[cell[b] * dim + k] - predictor_[cell[b] * dim + k]);
              g[cell[a] * dim + k] += d;
            }
      }
  }

  template <int dim>
  void InertiaTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    (void)project;  // the mass matrix is positive definite
    if (!active_)
      return;
    const auto &mesh = materials_.mesh();
    const auto &mass = unit_mass_coefficients<dim>();
    h.use_cell_blocks();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), [&](const tbb::blocked_range<std::size_t> &range) {
      for (std::size_t c = range.begin(); c != range.end(); ++c)
        {
          const double scale =
            materials_.of_cell(c).density * simplex_measure<dim, double>(cell_nodes<dim>(p.u, mesh.cells[c]));
          auto block = h.cell_block(c);
          for (int a = 0; a <= dim; ++a)
            for (int b = 0; b <= dim; ++b)
              for (int k = 0; k < dim; ++k)
                block(a * dim + k, b * dim + k) += scale * mass[a][b];
        }
    });
  }

  template <int dim>
  void InertiaTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block, const bool coupling,
                                                   ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!active_)
      return;
    constexpr int n           = dim * (dim + 1);
    const auto   &mesh        = materials_.mesh();
    const auto   &mass        = unit_mass_coefficients<dim>();
    const bool    uncorrected = form_ == InertiaForm::uncorrected && predictor_kind_ == Predictor::nodal;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto                 &cell = mesh.cells[c];
        const double                rho  = materials_.of_cell(c).density;
        Eigen::Matrix<double, n, 1> q_x;
        Eigen::Matrix<double, n, n> q_xx = Eigen::Matrix<double, n, n>::Zero();
        for (int a = 0; a <= dim; ++a)
          for (int k = 0; k < dim; ++k)
            {
              double s = 0;
              for (int b = 0; b <= dim; ++b)
                {
                  s += mass[a][b] * (p.z[cell[b] * dim + k] - predictor_[cell[b] * dim + k]);
                  q_xx(a * dim + k, b * dim + k) = rho * mass[a][b];
                }
              q_x[a * dim + k] = rho * s;
            }
        add_measure_weighted_cell<dim>(c, cell, rho * kinetic_density<dim>(p.z, predictor_, cell, uncorrected), q_x, q_xx,
                                       cell_measure_derivatives<dim>(p.u, cell), block, coupling, d);
      }
  }

  template <int dim>
  void InertiaTerm<dim>::add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const
  {
    if (!active_)
      return;
    const auto &mesh        = materials_.mesh();
    const bool  uncorrected = form_ == InertiaForm::uncorrected && predictor_kind_ == Predictor::nodal;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      add_measure_weighted_gradient<dim>(
        mesh.cells[c], materials_.of_cell(c).density * kinetic_density<dim>(p.z, predictor_, mesh.cells[c], uncorrected),
        cell_measure_gradient<dim>(p.u, mesh.cells[c]), d.gu);
  }

  template class InertiaTerm<1>;
  template class InertiaTerm<2>;
  template class InertiaTerm<3>;
} // namespace ritr
