#pragma once
// Meshes and helpers shared by the transfer tests (no deal.II: the transfer module is pure
// C++/Eigen, so its tests build meshes themselves).
#include <ritr/common/small_matrix.h>
#include <ritr/transfer/transfer_operator.h>

#include "finite_difference.h"

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace ritr::transfer::test
{
  template <int dim>
  struct BoxMesh
  {
    std::vector<std::array<unsigned int, dim + 1>> cells;
    Eigen::VectorXd                                nodes; // flat, node-major
    int                                            subdivisions = 1;

    unsigned int n_nodes() const { return nodes.size() / dim; }
    double       spacing() const { return 1.0 / subdivisions; }
  };

  // Node positions of a cell, for orientation checks.
  template <int dim>
  std::array<std::array<double, dim>, dim + 1> cell_nodes(const Eigen::VectorXd                    &u,
                                                          const std::array<unsigned int, dim + 1> &cell)
  {
    std::array<std::array<double, dim>, dim + 1> m;
    for (int a = 0; a <= dim; ++a)
      for (int k = 0; k < dim; ++k)
        m[a][k] = u[cell[a] * dim + k];
    return m;
  }

  // [0,1]^dim split into n^dim cubes, each cut into dim! simplices (Kuhn/Freudenthal),
  // positively oriented.
  template <int dim>
  BoxMesh<dim> box_mesh(const int n)
  {
    BoxMesh<dim> mesh;
    mesh.subdivisions = n;
    int n_per_axis    = n + 1;
    int n_nodes       = 1;
    for (int k = 0; k < dim; ++k)
      n_nodes *= n_per_axis;
    mesh.nodes.resize(n_nodes * dim);
    auto index = [&](const std::array<int, dim> &ijk) {
      int id = 0;
      for (int k = dim - 1; k >= 0; --k)
        id = id * n_per_axis + ijk[k];
      return id;
    };
    for (int id = 0; id < n_nodes; ++id)
      for (int k = 0, r = id; k < dim; ++k, r /= n_per_axis)
        mesh.nodes[id * dim + k] = double(r % n_per_axis) / n;

    std::array<int, dim> perm;
    std::iota(perm.begin(), perm.end(), 0);
    std::vector<std::array<int, dim>> perms;
    do
      perms.push_back(perm);
    while (std::next_permutation(perm.begin(), perm.end()));

    int n_cubes = 1;
    for (int k = 0; k < dim; ++k)
      n_cubes *= n;
    for (int cube = 0; cube < n_cubes; ++cube)
      {
        std::array<int, dim> corner;
        for (int k = 0, r = cube; k < dim; ++k, r /= n)
          corner[k] = r % n;
        for (const auto &p : perms)
          {
            std::array<unsigned int, dim + 1> cell;
            std::array<int, dim>              v = corner;
            cell[0]                             = index(v);
            for (int j = 0; j < dim; ++j)
              {
                v[p[j]] += 1;
                cell[j + 1] = index(v);
              }
            if (simplex_measure<dim, double>(cell_nodes<dim>(mesh.nodes, cell)) < 0)
              std::swap(cell[0], cell[1]);
            mesh.cells.push_back(cell);
          }
      }
    return mesh;
  }

  template <int dim>
  double min_measure(const BoxMesh<dim> &mesh, const Eigen::VectorXd &u)
  {
    double m = std::numeric_limits<double>::infinity();
    for (const auto &cell : mesh.cells)
      m = std::min(m, simplex_measure<dim, double>(cell_nodes<dim>(u, cell)));
    return m;
  }

  inline bool on_boundary(const double v) { return v < 1e-12 || v > 1 - 1e-12; }

  // Random displacement of amplitude `amplitude * spacing` per component. Components normal
  // to a box face the node lies on are kept, so boundary nodes slide within their facets
  // (and edges, corners stay) and the domain is unchanged. With interior_only, boundary
  // nodes do not move at all.
  template <int dim>
  Eigen::VectorXd jitter(const BoxMesh<dim> &mesh, const Eigen::VectorXd &u, const double amplitude,
                         const unsigned int seed, const bool interior_only = false)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> d(-amplitude * mesh.spacing(), amplitude * mesh.spacing());
    Eigen::VectorXd                        v = u;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        bool boundary = false;
        for (int k = 0; k < dim; ++k)
          boundary = boundary || on_boundary(mesh.nodes[i * dim + k]);
        for (int k = 0; k < dim; ++k)
          {
            const double delta = d(rng);
            if (on_boundary(mesh.nodes[i * dim + k]) || (interior_only && boundary))
              continue;
            v[i * dim + k] += delta;
          }
      }
    return v;
  }

  // The node closest to point p.
  template <int dim>
  unsigned int nearest_node(const BoxMesh<dim> &mesh, const Eigen::Matrix<double, dim, 1> &p)
  {
    unsigned int best = 0;
    for (unsigned int i = 1; i < mesh.n_nodes(); ++i)
      if ((mesh.nodes.template segment<dim>(i * dim) - p).norm() <
          (mesh.nodes.template segment<dim>(best * dim) - p).norm())
        best = i;
    return best;
  }

  inline Eigen::VectorXd random_field(const Eigen::Index size, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> d(-1, 1);
    Eigen::VectorXd                        v(size);
    for (Eigen::Index i = 0; i < size; ++i)
      v[i] = d(rng);
    return v;
  }

  // A nodal field f(u_i) = M u_i + c (every component linear in position).
  template <int dim>
  Eigen::VectorXd linear_field(const Eigen::VectorXd &u, const Eigen::Matrix<double, dim, dim> &M,
                               const Eigen::Matrix<double, dim, 1> &c)
  {
    Eigen::VectorXd f(u.size());
    for (Eigen::Index i = 0; i < u.size() / dim; ++i)
      f.template segment<dim>(i * dim) = M * u.template segment<dim>(i * dim) + c;
    return f;
  }

  using ritr::test_support::relative_error;

  // Central differences of a function of the candidate mesh with the located old cells
  // frozen. `evaluate(u)` must call set_candidate(u) on `op` and return the quantity. A
  // component is skipped (its column left NaN) when a +-step moves any quadrature point
  // into another old cell: the analytic derivatives are those of the fixed assignment.
  template <int dim>
  struct FrozenFiniteDifference
  {
    Eigen::MatrixXd jacobian; // column j = d f / d u_j
    int             n_skipped = 0;
  };

  template <int dim>
  FrozenFiniteDifference<dim>
  fd_in_u(TransferOperator<dim> &op, const Eigen::VectorXd &u, const double step,
          const std::function<Eigen::VectorXd(const Eigen::VectorXd &)> &evaluate)
  {
    FrozenFiniteDifference<dim> r;
    op.set_candidate(u);
    const std::vector<int> base = op.located_cells();
    Eigen::VectorXd        v    = u;
    for (Eigen::Index j = 0; j < u.size(); ++j)
      {
        v[j]                     = u[j] + step;
        const Eigen::VectorXd fp = evaluate(v);
        const bool            same_p = op.located_cells() == base;
        v[j]                     = u[j] - step;
        const Eigen::VectorXd fm = evaluate(v);
        const bool            same_m = op.located_cells() == base;
        v[j]                     = u[j];
        if (j == 0)
          r.jacobian.resize(fp.size(), u.size());
        if (same_p && same_m)
          r.jacobian.col(j) = (fp - fm) / (2 * step);
        else
          {
            r.jacobian.col(j).setConstant(std::nan(""));
            ++r.n_skipped;
          }
      }
    op.set_candidate(u);
    return r;
  }

  // Relative error over the columns that were not skipped.
  inline double relative_error_where_defined(const Eigen::MatrixXd &analytic, const Eigen::MatrixXd &fd)
  {
    Eigen::MatrixXd a = analytic, f = fd;
    for (Eigen::Index j = 0; j < fd.cols(); ++j)
      if (std::isnan(fd(0, j)))
        {
          a.col(j).setZero();
          f.col(j).setZero();
        }
    return relative_error(a, f);
  }
  template <int dim>
  struct Scenario
  {
    BoxMesh<dim>    mesh;
    Eigen::VectorXd u_old, u;
  };

  // (a) the candidate is a small random perturbation of a jittered old mesh.
  template <int dim>
  Scenario<dim> jittered_scenario(const int n)
  {
    Scenario<dim> s;
    s.mesh  = box_mesh<dim>(n);
    s.u_old = jitter(s.mesh, s.mesh.nodes, 0.15, 21);
    s.u     = jitter(s.mesh, s.u_old, 0.15, 22, /*interior_only=*/true);
    return s;
  }

  // (b) some nodes moved far (~0.3-0.45 spacing) so that candidate cells cross several old
  // cells, with thin candidate/old intersections where edges almost coincide.
  template <int dim>
  Scenario<dim> sliver_scenario(const int n)
  {
    Scenario<dim> s;
    s.mesh  = box_mesh<dim>(n);
    s.u_old = jitter(s.mesh, s.mesh.nodes, 0.03, 31);
    s.u     = jitter(s.mesh, s.u_old, 0.01, 32, true);
    const double h = s.mesh.spacing();
    if constexpr (dim == 1)
      {
        // Cell [i, i+1] grows over both neighbours: it then covers three old cells.
        const unsigned int i = n / 2;
        s.u[i] -= 0.45 * h;
        s.u[i + 1] += 0.45 * h;
      }
    else if constexpr (dim == 2)
      {
        const unsigned int a = nearest_node(s.mesh, Eigen::Vector2d(h, h));
        const unsigned int b = nearest_node(s.mesh, Eigen::Vector2d(2 * h, h));
        s.u.template segment<2>(a * 2) += h * Eigen::Vector2d(0.33, 0.3);
        s.u.template segment<2>(b * 2) += h * Eigen::Vector2d(-0.2, 0.42);
      }
    else
      {
        const unsigned int a = nearest_node(s.mesh, Eigen::Vector3d(h, h, h));
        s.u.template segment<3>(a * 3) += h * Eigen::Vector3d(0.3, 0.28, 0.26);
      }
    return s;
  }

  // (c) the old boundary nodes are pulled inward off their box faces (by up to 0.1 spacing)
  // while the candidate's boundary nodes slide within the exact faces, so quadrature points
  // near the boundary lie outside the old domain and use the nearest cell's extension.
  template <int dim>
  Scenario<dim> outside_scenario(const int n)
  {
    Scenario<dim> s;
    s.mesh  = box_mesh<dim>(n);
    s.u_old = jitter(s.mesh, s.mesh.nodes, 0.1, 41);
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> d(0, 0.1 * s.mesh.spacing());
    for (unsigned int i = 0; i < s.mesh.n_nodes(); ++i)
      for (int k = 0; k < dim; ++k)
        if (on_boundary(s.mesh.nodes[i * dim + k]))
          s.u_old[i * dim + k] += s.mesh.nodes[i * dim + k] < 0.5 ? d(rng) : -d(rng);
    s.u = jitter(s.mesh, s.mesh.nodes, 0.1, 43);
    return s;
  }

} // namespace ritr::transfer::test
