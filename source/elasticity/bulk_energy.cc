#include <ritr/common/psd_projection.h>
#include <ritr/elasticity/bulk_energy.h>
#include <ritr/mesh/simplex_rules.h>

#include <Eigen/Cholesky>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

namespace ritr
{
  template <int dim>
  const std::array<std::array<double, dim + 1>, dim + 1> &unit_mass_coefficients()
  {
    static const auto coefficients = [] {
      // Degree-2 rule: exact for products of two linear shape functions.
      const auto rule = gauss_simplex_rule<dim>(2);
      std::array<std::array<double, dim + 1>, dim + 1> m{};
      double total = 0;
      for (unsigned int p = 0; p < rule.size(); ++p)
        {
          total += rule.weights[p];
          for (int a = 0; a <= dim; ++a)
            for (int b = 0; b <= dim; ++b)
              m[a][b] += rule.weights[p] * rule.points[p][a] * rule.points[p][b];
        }
      for (auto &row : m)
        for (auto &v : row)
          v /= total;
      return m;
    }();
    return coefficients;
  }

  namespace
  {
    // Geometry of one P1 cell needed by the fast x-derivative path.
    template <int dim>
    struct CellGeometry
    {
      double                              measure;
      std::array<std::array<double, dim>, dim + 1> shape_gradients;  // dN_a/dX_j
      SmallMatrix<dim, double>            F;
    };

    template <int dim>
    CellGeometry<dim> cell_geometry(const CellNodes<dim, double> &x, const CellNodes<dim, double> &u)
    {
      CellGeometry<dim> g;
      const auto dm     = edge_matrix<dim, double>(u);
      const auto dm_inv = inverse<dim, double>(dm);
      g.measure         = determinant<dim, double>(dm) / factorial(dim);
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

    // Psi, dPsi/dF and d2Psi/dF2 at F (flattened row-major: index k*dim + j).
    template <int dim>
    SecondOrderDual<dim * dim> energy_density_derivatives(const Material &m, const SmallMatrix<dim, double> &F)
    {
      SmallMatrix<dim, SecondOrderDual<dim * dim>> f;
      for (int k = 0; k < dim; ++k)
        for (int j = 0; j < dim; ++j)
          f[k][j] = SecondOrderDual<dim * dim>::variable(k * dim + j, F[k][j]);
      return strain_energy_density<dim, SecondOrderDual<dim * dim>>(m, f);
    }

    // d2Psi/dF2 (flattened as above). Neo-Hookean in closed form -- the dual numbers cost
    // as much as the rest of an element's Hessian --
    //   mu I + lambda F^-T (x) F^-T + (mu - lambda ln J) dF^-T/dF-term,
    // i.e. H_(ij)(kl) = mu d_ik d_jl + lambda Finv_ji Finv_lk + (mu - lambda ln J) Finv_jk Finv_li;
    // the other models through the dual numbers.
    template <int dim>
    Eigen::Matrix<double, dim * dim, dim * dim> energy_density_hessian(const Material &m, const SmallMatrix<dim, double> &F)
    {
      if (m.model != MaterialModel::neo_hookean)
        return energy_density_derivatives<dim>(m, F).hess;
      const double mu = m.mu(dim), lambda = m.lambda(dim);
      const auto   f_inv = inverse<dim, double>(F);
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
    void gather(const Eigen::VectorXd &v, const std::array<unsigned int, dim + 1> &cell,
                CellNodes<dim, double> &out)
    {
      for (int a = 0; a <= dim; ++a)
        for (int k = 0; k < dim; ++k)
          out[a][k] = v[cell[a] * dim + k];
    }

    constexpr std::size_t grain = 256;
  } // namespace

  template <int dim>
  BulkEnergy<dim>::BulkEnergy(const SimplexMesh<dim> &mesh, const std::vector<Material> &materials)
    : mesh_(mesh)
    , materials_(materials)
    , x_pred_(Eigen::VectorXd::Zero(mesh.reference.size()))
  {
    for (const unsigned int id : mesh.cell_material)
      if (id >= materials_.size())
        throw std::runtime_error("cells have material id " + std::to_string(id) +
                                 " but no material with that id is defined");
  }

  // Reductions below are deterministic: the cell range is split the same way and partial
  // sums are joined in the same order on any number of threads, so a scene gives the same
  // iterates on one thread and on many.
  template <int dim>
  double BulkEnergy<dim>::value(const Eigen::VectorXd &x, const Eigen::VectorXd &u) const
  {
    return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, mesh_.n_cells(), grain), 0.0,
      [&](const tbb::blocked_range<std::size_t> &range, double sum) {
        CellNodes<dim, double> xe, ue, pe;
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            gather<dim>(x, mesh_.cells[c], xe);
            gather<dim>(u, mesh_.cells[c], ue);
            gather<dim>(x_pred_, mesh_.cells[c], pe);
            sum += cell_energy<dim, double>(cell_material(c), weights_, xe, ue, pe);
          }
        return sum;
      },
      std::plus<double>());
  }

  template <int dim>
  void BulkEnergy<dim>::add_gradient(const Eigen::VectorXd &x, const Eigen::VectorXd &u,
                                     Eigen::VectorXd &g) const
  {
    // Each cell writes its own slice of cell_gradients in parallel; the scatter into g then
    // runs in cell order, so the sum is the same on any number of threads.
    constexpr int n = dim * (dim + 1);
    std::vector<double> cell_gradients(static_cast<std::size_t>(mesh_.n_cells()) * n);
    const auto &mass = unit_mass_coefficients<dim>();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh_.n_cells(), grain),
                      [&](const tbb::blocked_range<std::size_t> &range) {
                        CellNodes<dim, double> xe, ue, pe;
                        for (std::size_t c = range.begin(); c != range.end(); ++c)
                          {
                            const auto &cell = mesh_.cells[c];
                            const auto &mat  = cell_material(c);
                            gather<dim>(x, cell, xe);
                            gather<dim>(u, cell, ue);
                            gather<dim>(x_pred_, cell, pe);
                            const auto geo = cell_geometry<dim>(xe, ue);
                            const auto P   = first_piola_stress<dim>(mat, geo.F);
                            double    *out = cell_gradients.data() + c * n;
                            for (int a = 0; a <= dim; ++a)
                              for (int k = 0; k < dim; ++k)
                                {
                                  double d = 0;
                                  for (int j = 0; j < dim; ++j)
                                    d += P[k][j] * geo.shape_gradients[a][j];
                                  d -= mat.density / (dim + 1) * weights_.gravity[k];
                                  d *= weights_.potential * geo.measure;
                                  if (weights_.inertia != 0.0)
                                    for (int b = 0; b <= dim; ++b)
                                      d += weights_.inertia * mat.density * geo.measure * mass[a][b] *
                                           (xe[b][k] - pe[b][k]);
                                  out[a * dim + k] = d;
                                }
                          }
                      });
    for (std::size_t c = 0; c < mesh_.n_cells(); ++c)
      for (int i = 0; i < n; ++i)
        g[mesh_.cells[c][i / dim] * dim + i % dim] += cell_gradients[c * n + i];
  }

  template <int dim>
  void BulkEnergy<dim>::add_hessian(const Eigen::VectorXd &x, const Eigen::VectorXd &u,
                                    const bool project, Triplets &hessian) const
  {
    constexpr int n = dim * (dim + 1);
    using Local     = Eigen::Matrix<double, n, n>;
    const auto &mass = unit_mass_coefficients<dim>();
    // Every cell writes its own n*n slice of the triplet list, so the scatter runs in
    // parallel with the element computations.
    const std::size_t offset = hessian.size();
    hessian.resize(offset + static_cast<std::size_t>(mesh_.n_cells()) * n * n);
    tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mesh_.n_cells(), grain),
      [&](const tbb::blocked_range<std::size_t> &range) {
        CellNodes<dim, double> xe, ue;
        Local                  block;
        for (std::size_t c = range.begin(); c != range.end(); ++c)
          {
            const auto &mat  = cell_material(c);
            const auto &cell = mesh_.cells[c];
            gather<dim>(x, cell, xe);
            gather<dim>(u, cell, ue);
            const auto geo = cell_geometry<dim>(xe, ue);
            Eigen::Matrix<double, dim * dim, dim * dim> psi_hessian = energy_density_hessian<dim>(mat, geo.F);
            // The map F -> x is linear, so a PSD density Hessian gives a PSD element block;
            // a successful Cholesky factorization proves it already is and saves the
            // eigendecomposition.
            if (project && Eigen::LLT<decltype(psi_hessian)>(psi_hessian).info() != Eigen::Success)
              psi_hessian = project_to_psd(psi_hessian);
            // dF/dx: F_kj = sum_a x_ak dN_a/dX_j.
            Eigen::Matrix<double, dim * dim, n> dF_dx = Eigen::Matrix<double, dim * dim, n>::Zero();
            for (int a = 0; a <= dim; ++a)
              for (int k = 0; k < dim; ++k)
                for (int j = 0; j < dim; ++j)
                  dF_dx(k * dim + j, a * dim + k) = geo.shape_gradients[a][j];
            block.noalias() = (weights_.potential * geo.measure) * dF_dx.transpose() * psi_hessian * dF_dx;
            for (int a = 0; a <= dim; ++a)
              for (int b = 0; b <= dim; ++b)
                for (int k = 0; k < dim; ++k)
                  block(a * dim + k, b * dim + k) += weights_.inertia * mat.density * geo.measure * mass[a][b];
            auto *out = hessian.data() + offset + c * n * n;
            for (int i = 0; i < n; ++i)
              for (int j = 0; j < n; ++j)
                *out++ = Eigen::Triplet<double>(cell[i / dim] * dim + i % dim, cell[j / dim] * dim + j % dim,
                                                block(i, j));
          }
      });
  }

  template <int dim>
  void BulkEnergy<dim>::joint_derivatives(const Eigen::VectorXd &x, const Eigen::VectorXd &u,
                                          const ReferenceBlock block, JointDerivatives &out) const
  {
    constexpr int n = dim * (dim + 1);
    using Dual      = SecondOrderDual<2 * n>;
    out.gx          = Eigen::VectorXd::Zero(x.size());
    out.gu          = Eigen::VectorXd::Zero(u.size());
    std::vector<Dual> cell_values(mesh_.n_cells());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh_.n_cells(), 64),
                      [&](const tbb::blocked_range<std::size_t> &range) {
                        CellNodes<dim, double> pe;
                        CellNodes<dim, Dual>   xe, ue;
                        for (std::size_t c = range.begin(); c != range.end(); ++c)
                          {
                            const auto &cell = mesh_.cells[c];
                            gather<dim>(x_pred_, cell, pe);
                            for (int a = 0; a <= dim; ++a)
                              for (int k = 0; k < dim; ++k)
                                {
                                  xe[a][k] = Dual::variable(a * dim + k, x[cell[a] * dim + k]);
                                  ue[a][k] = Dual::variable(n + a * dim + k, u[cell[a] * dim + k]);
                                }
                            cell_values[c] =
                              cell_energy<dim, Dual>(cell_material(c), weights_, xe, ue, pe);
                          }
                      });
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      {
        const auto &cell = mesh_.cells[c];
        const auto &v    = cell_values[c];
        const auto  dof  = [&](int i) { return cell[i / dim] * dim + i % dim; };
        Eigen::Matrix<double, n, n> huu = v.hess.template bottomRightCorner<n, n>();
        if (block == ReferenceBlock::following)
          huu += v.hess.template topLeftCorner<n, n>() + v.hess.template topRightCorner<n, n>() +
                 v.hess.template bottomLeftCorner<n, n>();
        for (int i = 0; i < n; ++i)
          {
            out.gx[dof(i)] += v.grad[i];
            out.gu[dof(i)] += v.grad[n + i];
            for (int j = 0; j < n; ++j)
              {
                out.hxx.emplace_back(dof(i), dof(j), v.hess(i, j));
                out.hxu.emplace_back(dof(i), dof(j), v.hess(i, n + j));
                out.huu.emplace_back(dof(i), dof(j), huu(i, j));
              }
          }
      }
  }

  template <int dim>
  Eigen::VectorXd BulkEnergy<dim>::nodal_masses(const Eigen::VectorXd &u) const
  {
    Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh_.n_nodes());
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      {
        const double share = cell_material(c).density *
                             simplex_measure<dim, double>(cell_nodes<dim>(u, mesh_.cells[c])) / (dim + 1);
        for (const unsigned int node : mesh_.cells[c])
          m[node] += share;
      }
    return m;
  }

  template class BulkEnergy<1>;
  template class BulkEnergy<2>;
  template class BulkEnergy<3>;
  template const std::array<std::array<double, 2>, 2> &unit_mass_coefficients<1>();
  template const std::array<std::array<double, 3>, 3> &unit_mass_coefficients<2>();
  template const std::array<std::array<double, 4>, 4> &unit_mass_coefficients<3>();
} // namespace ritr
