#include <ritr/elasticity/cell_energy.h>
#include <ritr/elasticity/density_hessian.h>
#include <ritr/terms/elasticity_term.h>

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

    template <int dim>
    void gather(const Eigen::VectorXd &v, const std::array<unsigned int, dim + 1> &cell, CellNodes<dim, double> &out)
    {
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          out[a][k] = v[cell[a] * dim + k];
    }

    constexpr std::size_t grain = 256;

    // Adds per-cell vectors (cell_vector(c, xe, ue, out) fills the dim * (dim + 1) entries of
    // cell c) into g: computed in parallel, scattered in cell order, so that the sum is the same
    // on any number of threads.
    template <int dim, typename CellVector>
    void add_cell_vectors(const SimplexMesh<dim> &mesh, const TermPoint &p, Eigen::VectorXd &g,
                          const CellVector &cell_vector)
    {
      constexpr int       n = dim * (dim + 1);
      std::vector<double> cell_vectors(static_cast<std::size_t>(mesh.n_cells()) * n);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain),
                        [&](const tbb::blocked_range<std::size_t> &range) {
                          CellNodes<dim, double> xe, ue;
                          for (std::size_t c = range.begin(); c != range.end(); ++c)
                            {
                              gather<dim>(p.z, mesh.cells[c], xe);
                              gather<dim>(p.u, mesh.cells[c], ue);
                              cell_vector(c, xe, ue, cell_vectors.data() + c * n);
                            }
                        });
      for (std::size_t c = 0; c < mesh.n_cells(); ++c)
        for (int i = 0; i < n; ++i)
          g[mesh.cells[c][i / dim] * dim + i % dim] += cell_vectors[c * n + i];
    }
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
    add_cell_vectors<dim>(materials_.mesh(), p, g, [&](const std::size_t c, const auto &xe, const auto &ue, double *out) {
      const auto geo = cell_geometry<dim>(xe, ue);
      const auto P   = first_piola_stress<dim>(materials_.of_cell(c), geo.F);
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          {
            double d = 0;
            for (int j = 0; j < dim; ++j)
              d += P[k][j] * geo.shape_gradients[a][j];
            out[a * dim + k] = weight_ * geo.measure * d;
          }
    });
  }

  template <int dim>
  void ElasticityTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    const auto &mesh = materials_.mesh();
    h.use_cell_blocks();
    tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), [&](const tbb::blocked_range<std::size_t> &range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            auto cell = cell_hessian(p, c);
            if (project)
              if (const auto change = density_hessian_projection<dim>(materials_.of_cell(c), cell.F, cell.density_hessian))
                cell.density_hessian += *change;
            h.cell_block(c).noalias() += cell.element_matrix(cell.density_hessian);
          }
      });
  }

  template <int dim>
  void ElasticityTerm<dim>::add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const
  {
    const auto &mesh = materials_.mesh();
    h.use_cell_blocks();
    h.use_change_blocks();
    tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mesh.n_cells(), grain), [&](const tbb::blocked_range<std::size_t> &range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            const auto cell = cell_hessian(p, c);
            h.cell_block(c).noalias() += cell.element_matrix(cell.density_hessian);
            // Only the cells the projection changes (compressed ones) get a change block.
            if (const auto change = density_hessian_projection<dim>(materials_.of_cell(c), cell.F, cell.density_hessian))
              h.change_block(c).noalias() += cell.element_matrix(*change);
          }
      });
  }

  template <int dim>
  typename ElasticityTerm<dim>::CellHessian ElasticityTerm<dim>::cell_hessian(const TermPoint &p, const std::size_t c) const
  {
    const auto            &mesh = materials_.mesh();
    CellNodes<dim, double> xe, ue;
    gather<dim>(p.z, mesh.cells[c], xe);
    gather<dim>(p.u, mesh.cells[c], ue);
    const auto  geo = cell_geometry<dim>(xe, ue);
    CellHessian cell;
    cell.F               = geo.F;
    cell.density_hessian = energy_density_hessian<dim>(materials_.of_cell(c), geo.F);
    cell.shape_gradients = geo.shape_gradients;
    cell.scale           = weight_ * geo.measure;
    return cell;
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

  template <int dim>
  void ElasticityTerm<dim>::add_reference_gradient(const TermPoint &p, ReferenceDerivativeAssembly<dim> &d) const
  {
    // Moving the reference nodes by du changes the edge matrix by G Dm with
    // G = sum_a du_a (x) grad N_a, so that dF = -F G and d|T| = |T| tr G: the cell's energy
    // changes by |T| (Psi I - F^T P) : G, the Eshelby (energy-momentum) stress against G.
    add_cell_vectors<dim>(materials_.mesh(), p, d.gu, [&](const std::size_t c, const auto &xe, const auto &ue, double *out) {
      const auto      geo      = cell_geometry<dim>(xe, ue);
      const Material &material = materials_.of_cell(c);
      const auto      P        = first_piola_stress<dim>(material, geo.F);
      const double    psi      = strain_energy_density<dim, double>(material, geo.F);
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          {
            double s = 0;
            for (int j = 0; j < dim; ++j)
              {
                double eshelby = k == j ? psi : 0.0;  // (Psi I - F^T P)_kj
                for (int i = 0; i < dim; ++i)
                  eshelby -= geo.F[i][k] * P[i][j];
                s += eshelby * geo.shape_gradients[a][j];
              }
            out[a * dim + k] = weight_ * geo.measure * s;
          }
    });
  }

  template class ElasticityTerm<1>;
  template class ElasticityTerm<2>;
  template class ElasticityTerm<3>;
} // namespace ritr
