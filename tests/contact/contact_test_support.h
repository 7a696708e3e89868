#pragma once
// Helpers shared by the contact module's unit tests: the test program's random generator,
// small scenes (a collision surface with its vertex positions) and the scene builders more
// than one test uses, random constraint weights, dense Hessians, and finite-difference
// checks of assembled derivatives w.r.t. a position matrix. The finite differences
// themselves come from tests/support/finite_difference.h.
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/constraints.h>

#include "finite_difference.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace ritr::contact::test_support
{
  using namespace ritr::test_support; // fd_gradient, fd_jacobian, relative_error

  template <int dim>
  using Vec = Eigen::Matrix<double, dim, 1>;

  // ---- Random numbers ---------------------------------------------------------------------

  // Seed of the test program's generator. Each test file defines it (one per executable),
  // so every file keeps its own reproducible sequence:
  //   const std::mt19937::result_type ritr::contact::test_support::rng_seed = 7;
  extern const std::mt19937::result_type rng_seed;

  inline std::mt19937 &rng()
  {
    static std::mt19937 gen(rng_seed);
    return gen;
  }

  inline double uniform(const double a = -1.0, const double b = 1.0)
  {
    return std::uniform_real_distribution<double>(a, b)(rng());
  }

  // Entries uniform in [-half, half).
  template <int n>
  Vec<n> random_vector(const double half = 1.0)
  {
    Vec<n> v;
    for (int i = 0; i < n; ++i)
      v[i] = uniform(-half, half);
    return v;
  }

  // ---- Scenes -----------------------------------------------------------------------------

  template <int dim>
  struct Scene
  {
    CollisionSurface<dim> surface;
    std::vector<Vec<dim>> points;

    int add_vertex(const Vec<dim> &x, const bool obstacle, const int body = 0)
    {
      points.push_back(x);
      surface.is_obstacle.push_back(obstacle);
      surface.body_id.push_back(body);
      return surface.n_vertices++;
    }
    Eigen::MatrixXd V() const
    {
      Eigen::MatrixXd M(points.size(), dim);
      for (std::size_t i = 0; i < points.size(); ++i)
        M.row(i) = points[i].transpose();
      return M;
    }
  };

  // 2D: jittered regular polygon, counter-clockwise boundary.
  inline void add_polygon(Scene<2> &s, const Vec<2> &center, const double radius, const int n,
                          const double jitter, const bool obstacle, const int body)
  {
    const double phase = uniform(0, 6.28);
    const int    first = s.surface.n_vertices;
    for (int i = 0; i < n; ++i)
      {
        const double a = phase + 2 * M_PI * i / n;
        const double r = radius * (1 + jitter * uniform());
        s.add_vertex(center + r * Vec<2>(std::cos(a), std::sin(a)), obstacle, body);
      }
    for (int i = 0; i < n; ++i)
      s.surface.edges.push_back({{first + i, first + (i + 1) % n}});
  }

  // 3D: jittered, randomly rotated octahedron.
  inline void add_octahedron(Scene<3> &s, const Vec<3> &center, const double radius,
                             const double jitter, const bool obstacle, const int body)
  {
    const Eigen::Matrix3d R =
      Eigen::AngleAxisd(uniform(0, 6.28), Vec<3>(uniform(), uniform(), uniform()).normalized())
        .toRotationMatrix();
    const int first = s.surface.n_vertices;
    for (int k = 0; k < 3; ++k)
      for (const double sign : {1.0, -1.0})
        {
          Vec<3> p = Vec<3>::Zero();
          p[k]     = sign * radius * (1 + jitter * uniform());
          s.add_vertex(center + R * p, obstacle, body);
        }
    // Vertices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto &f : faces)
      s.surface.faces.push_back({{first + f[0], first + f[1], first + f[2]}});
    s.surface.edges = edges_of_faces(s.surface.faces);
  }

  // 3D: obstacle square [-half, half]^2 at height z (two triangles).
  inline void add_ground(Scene<3> &s, const double z, const double half)
  {
    const int a = s.add_vertex(Vec<3>(-half, -half, z), true, -1);
    const int b = s.add_vertex(Vec<3>(half, -half, z), true, -1);
    const int c = s.add_vertex(Vec<3>(half, half, z), true, -1);
    const int d = s.add_vertex(Vec<3>(-half, half, z), true, -1);
    s.surface.faces.push_back({{a, b, c}});
    s.surface.faces.push_back({{a, c, d}});
    s.surface.edges = edges_of_faces(s.surface.faces);
  }

  // Two touching polygons and an obstacle polygon above them.
  inline Scene<2> scene_2d()
  {
    Scene<2> s;
    add_polygon(s, Vec<2>(0, 0), 1.0, 12, 0.05, false, 0);
    add_polygon(s, Vec<2>(2.1, 0.1), 1.0, 9, 0.05, false, 1);
    add_polygon(s, Vec<2>(1.0, 1.75), 0.8, 7, 0.05, true, 2);
    return s;
  }

  // Two touching octahedra resting near an obstacle ground.
  inline Scene<3> scene_3d()
  {
    Scene<3> s;
    add_octahedron(s, Vec<3>(0, 0, 0), 1.0, 0.1, false, 0);
    add_octahedron(s, Vec<3>(1.35, 0.2, 0.3), 0.7, 0.1, false, 1);
    add_ground(s, -0.95, 3.0);
    return s;
  }

  // ---- Weights, matrices ------------------------------------------------------------------

  inline ConstraintWeights random_weights(const int n_vertices, const int n_edges)
  {
    ConstraintWeights w;
    for (int i = 0; i < n_vertices; ++i)
      w.vertex_weights.push_back(uniform(0.5, 2.0));
    for (int i = 0; i < n_edges; ++i)
      w.edge_weights.push_back(uniform(0.5, 2.0));
    return w;
  }

  inline Eigen::MatrixXd dense(const std::vector<Eigen::Triplet<double>> &t, const int n)
  {
    return ritr::test_support::dense(t, n, n);
  }

  // Position matrix (one row per vertex) <-> vertex-major vector, the layout of assembled
  // gradients and Hessians.
  inline Eigen::MatrixXd reshape(const Eigen::VectorXd &x, const int dim)
  {
    Eigen::MatrixXd V(x.size() / dim, dim);
    for (int i = 0; i < V.rows(); ++i)
      for (int k = 0; k < dim; ++k)
        V(i, k) = x[i * dim + k];
    return V;
  }
  inline Eigen::VectorXd flatten(const Eigen::MatrixXd &V)
  {
    Eigen::VectorXd x(V.size());
    for (int i = 0; i < V.rows(); ++i)
      for (int k = 0; k < V.cols(); ++k)
        x[i * V.cols() + k] = V(i, k);
    return x;
  }

  // ---- Finite differences w.r.t. positions ------------------------------------------------

  using PositionEnergy   = std::function<double(const Eigen::MatrixXd &)>;
  using PositionGradient = std::function<Eigen::VectorXd(const Eigen::MatrixXd &)>;
  using PositionHessian =
    std::function<std::vector<Eigen::Triplet<double>>(const Eigen::MatrixXd &)>;

  // Central differences of energy(V) / gradient(V) w.r.t. the vertex-major entries of V.
  inline Eigen::VectorXd fd_position_gradient(const PositionEnergy  &energy,
                                              const Eigen::MatrixXd &V, const double step)
  {
    const int dim = static_cast<int>(V.cols());
    return fd_gradient([&](const Eigen::VectorXd &x) { return energy(reshape(x, dim)); },
                       flatten(V), step);
  }
  inline Eigen::MatrixXd fd_position_jacobian(const PositionGradient &gradient,
                                              const Eigen::MatrixXd &V, const double step)
  {
    const int dim = static_cast<int>(V.cols());
    return fd_jacobian([&](const Eigen::VectorXd &x) { return gradient(reshape(x, dim)); },
                       flatten(V), step);
  }

  // Assembled gradient and Hessian at V against central differences (step 1e-7) of the
  // energy and of the gradient: norm-relative errors below tol, the Hessian's relative to
  // max(|H|, hessian_scale); the gradient must be nonzero and the Hessian symmetric.
  inline void expect_assembled_derivatives_match_fd(const PositionEnergy   &energy,
                                                    const PositionGradient &gradient,
                                                    const PositionHessian  &hessian,
                                                    const Eigen::MatrixXd &V, const double tol,
                                                    const double hessian_scale = 0.0)
  {
    const int             n    = static_cast<int>(V.size());
    const Eigen::VectorXd g    = gradient(V);
    const Eigen::MatrixXd H    = dense(hessian(V), n);
    const double          h    = 1e-7;
    const Eigen::VectorXd g_fd = fd_position_gradient(energy, V, h);
    const Eigen::MatrixXd H_fd = fd_position_jacobian(gradient, V, h);
    EXPECT_GT(g.norm(), 0.0);
    EXPECT_LE((g - g_fd).norm(), tol * g.norm()) << "g    = " << g.transpose() << "\ng_fd = "
                                                 << g_fd.transpose();
    EXPECT_LE((H - H_fd).norm(), tol * std::max(H.norm(), hessian_scale));
    EXPECT_LE((H - H.transpose()).norm(), 1e-12 * H.norm());
  }
} // namespace ritr::contact::test_support
