#include <ritr/common/psd_projection.h>
#include <ritr/elasticity/cell_energy.h>
#include <ritr/terms/elasticity_term.h>

#include <Eigen/Cholesky>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

namespace ritr
{
  namespace
  {
    // Geometry of one P1 cell needed by the fast x-derivative path.
    template <int dim>
    struct CellGeometry
    {
      double                                       measure;
      std::array<std::array<double, dim>, dim + 1> shape_gradients;  // dN_a/dX_j
      SmallMatrix<dim, double>                     F;
    };

    template <int dim>
    CellGeometry<dim> cell_geometry(const CellNodes<dim, double> &x, const CellNodes<dim, double> &u)
    {
      CellGeometry<dim> g;
      const auto        dm     = edge_matrix<dim, double>(u);
      const auto        dm_inv = inverse<dim, double>(dm);
      g.measure                = determinant<dim, double>(dm) / factorial(dim);
      for (int j = 0; j < dim; ++j)
        {
          g.shape_gradients[0][j] = 0;
          for (int a = 1; a <= dim; ++a)
            {
              g.shape_gradients[a][j] = dm_inv[a - 1][j];
              g.shape_gradients[0][j] -= dm_inv[a - 1][j];
            }
        }
      g.F = multiply<dim, double>(edge_matrix<dim, double>(x), dm_inv);
      return g;
    }

    // d2Psi/dF2, flattened row-major (index k*dim + j). Neo-Hookean in closed form -- dual
    // numbers cost as much as the rest of an element's Hessian --
    //   H_(ij)(kl) = mu d_ik d_jl + lambda Finv_ji Finv_lk + (mu - lambda ln J) Finv_jk Finv_li;
    // the other models through dual numbers.
    template <int dim>
    Eigen::Matrix<double, dim * dim, dim * dim> energy_density_hessian(const Material &m, const SmallMatrix<dim, double> &F)
    {
      if (m.model != MaterialModel::neo_hookean)
        {
          SmallMatrix<dim, SecondOrderDual<dim * dim>> f;
          for (int k = 0; k < dim; ++k)
            for (int j = 0; j < dim; ++j)
              f[k][j] = SecondOrderDual<dim * dim>::variable(k * dim + j, F[k][j]);
          return strain_energy_density<dim, SecondOrderDual<dim * dim>>(m, f).hess;
        }
      const double mu = m.mu(dim), lambda = m.lambda(dim);
      const auto   f_inv     = inverse<dim, double>(F);
      const double curvature = mu - lambda * std::log(determinant<dim, double>(F));
      Eigen::Matrix<double, dim * dim, dim * dim> h;
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          for (int k = 0; k < dim; ++k)
            for (int l = 0; l < dim; ++l)
              h(i * dim + j, k * dim + l) = (i == k && j == l ? mu : 0.0) + lambda * f_inv[j][i] * f_inv[l][k] +
                                            curvature * f_inv[j][k] * f_inv[l][i];
      return h;
    }

    template <int dim>
    void gather(const Eigen::VectorXd &v, const std::array<unsigned int, dim + 1> &cell, CellNodes<dim, double> &out)
    {
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          out[a][k] = v[cell[a] * dim + k];
    }

    constexpr std::size_t grain = 256;
  } // namespace

  // Reductions are deterministic: the cell range is split the same way and partial sums are
  // joined in the same order on any number of threads (doc/method.md).
  template <int dim>
  double ElasticityTerm<dim>::value(const TermPoint &p) const
  {
    const auto &mesh = materials_.mesh();
    const double sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), 0.0,
      [&](const tbb::blocked_range<std::size_t> &range, double s) {
        CellNodes<dim, double> xe, ue;
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            gather<dim>(p.z, mesh.cells[c], xe);
            gather<dim>(p.u, mesh.cells[c], ue);
            s += strain_energy<dim, double>(materials_.of_cell(c), xe, ue);
          }
        return s;
      },
      std::plus<double>());
    return weight_ * sum;
  }

  template <int dim>
  void ElasticityTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    // Each cell writes its own slice in parallel; the scatter into g runs in cell order, so
    // the sum is the same on any number of threads.
    constexpr int       n    = dim * (dim + 1);
    const auto         &mesh = materials_.mesh();
    std::vector<double> cell_gradients(static_cast<std::size_t>(mesh.n_cells()) * n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain),
                      [&](const tbb::blocked_range<std::size_t> &range) {
                        CellNodes<dim, double> xe, ue;
                        for (std::size_t c = range.begin(); c != range.end(); ++c)
                          {
                            gather<dim>(p.z, mesh.cells[c], xe);
                            gather<dim>(p.u, mesh.cells[c], ue);
                            const auto geo = cell_geometry<dim>(xe, ue);
                            const auto P   = first_piola_stress<dim>(materials_.of_cell(c), geo.F);
                            double    *out = cell_gradients.data() + c * n;
                            for (int a = 0; a <= dim; ++a)
                              for (int k = 0; k < dim; ++k)
                                {
                                  double d = 0;
                                  for (int j = 0; j < dim; ++j)
                                    d += P[k][j] * geo.shape_gradients[a][j];
                                  out[a * dim + k] = weight_ * geo.measure * d;
                                }
                          }
                      });
    for (std::size_t c = 0; c < mesh.n_cells(); ++c)
      for (int i = 0; i < n; ++i)
        g[mesh.cells[c][i / dim] * dim + i % dim] += cell_gradients[c * n + i];
  }

  template <int dim>
  void ElasticityTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    constexpr int n    = dim * (dim + 1);
    const auto   &mesh = materials_.mesh();
    h.use_cell_blocks();
    tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), [&](const tbb::blocked_range<std::size_t> &range) {
        CellNodes<dim, double> xe, ue;
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            gather<dim>(p.z, mesh.cells[c], xe);
            gather<dim>(p.u, mesh.cells[c], ue);
            const auto geo         = cell_geometry<dim>(xe, ue);
            auto       psi_hessian = energy_density_hessian<dim>(materials_.of_cell(c), geo.F);
            // The map F -> x is linear, so a PSD density Hessian gives a PSD element block; a
            // successful Cholesky factorization proves it already is and saves the
            // eigendecomposition.
            if (project && Eigen::LLT<decltype(psi_hessian)>(psi_hessian).info() != Eigen::Success)
              psi_hessian = project_to_psd(psi_hessian);
            // dF/dx: F_kj = sum_a x_ak dN_a/dX_j.
            Eigen::Matrix<double, dim * dim, n> dF_dx = Eigen::Matrix<double, dim * dim, n>::Zero();
            for (int a = 0; a <= dim; ++a)
              for (int k = 0; k < dim; ++k)
                for (int j = 0; j < dim; ++j)
                  dF_dx(k * dim + j, a * dim + k) = geo.shape_gradients[a][j];
            h.cell_block(c).noalias() += (weight_ * geo.measure) * dF_dx.transpose() * psi_hessian * dF_dx;
          }
      });
  }

  template <int dim>
  void ElasticityTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block, const bool coupling,
                                                      ReferenceDerivativeAssembly<dim> &d) const
  {
    constexpr int n    = dim * (dim + 1);
    using Dual         = SecondOrderDual<2 * n>;
    const auto &mesh   = materials_.mesh();
    d.huu.use_cell_blocks();
    if (coupling)
      {
        d.hxx.use_cell_blocks();
        d.hxu.use_cell_blocks();
      }
    // Per cell the gradient in (x_e, u_e); the blocks go straight into the cell blocks.
    std::vector<double> cell_gradients(static_cast<std::size_t>(mesh.n_cells()) * 2 * n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.n_cells(), 64), [&](const tbb::blocked_range<std::size_t> &range) {
      CellNodes<dim, Dual> xe, ue;
      for (std::size_t c = range.begin(); c != range.end(); ++c)
        {
          const auto &cell = mesh.cells[c];
          for (int a = 0; a <= dim; ++a)
            for (int k = 0; k < dim; ++k)
              {
                xe[a][k] = Dual::variable(a * dim + k, p.z[cell[a] * dim + k]);
                ue[a][k] = Dual::variable(n + a * dim + k, p.u[cell[a] * dim + k]);
              }
          const Dual v = weight_ * strain_energy<dim, Dual>(materials_.of_cell(c), xe, ue);
          Eigen::Map<Eigen::Matrix<double, 2 * n, 1>>(cell_gradients.data() + c * 2 * n) = v.grad;
          auto huu = d.huu.cell_block(c);
          huu += v.hess.template bottomRightCorner<n, n>();
          if (block == ReferenceBlock::following)
            huu += v.hess.template topLeftCorner<n, n>() + v.hess.template topRightCorner<n, n>() +
                   v.hess.template bottomLeftCorner<n, n>();
          if (coupling)
            {
              d.hxx.cell_block(c) += v.hess.template topLeftCorner<n, n>();
              d.hxu.cell_block(c) += v.hess.template topRightCorner<n, n>();
            }
        }
    });
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      for (int i = 0; i < n; ++i)
        {
          const unsigned int dof = mesh.cells[c][i / dim] * dim + i % dim;
          d.gu[dof] += cell_gradients[c * 2 * n + n + i];
          if (coupling)
            d.gx[dof] += cell_gradients[c * 2 * n + i];
        }
  }

  template class ElasticityTerm<1>;
  template class ElasticityTerm<2>;
  template class ElasticityTerm<3>;
} // namespace ritr
