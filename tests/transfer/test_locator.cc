// OldMeshLocator: containment against brute force, deterministic resolution on shared
// faces, nearest-cell linear extension outside the domain, and the hinted fast path.
#include "transfer_test_support.h"

#include <ritr/transfer/old_mesh_locator.h>

#include <gtest/gtest.h>

using namespace ritr;
using namespace ritr::transfer;
using namespace ritr::transfer::test;

namespace
{
  template <int dim>
  using Point = Eigen::Matrix<double, dim, 1>;

  // Barycentric coordinates by solving the (d+1)x(d+1) system [p_b; 1] mu = [X; 1] directly
  // (independent of the locator's precomputed affine maps).
  template <int dim>
  Eigen::Matrix<double, dim + 1, 1> brute_barycentric(const Eigen::VectorXd &u,
                                                      const std::array<unsigned int, dim + 1> &cell,
                                                      const Point<dim> &X)
  {
    Eigen::Matrix<double, dim + 1, dim + 1> S;
    for (int b = 0; b <= dim; ++b)
      {
        S.col(b).template head<dim>() = u.template segment<dim>(cell[b] * dim);
        S(dim, b)                     = 1;
      }
    Eigen::Matrix<double, dim + 1, 1> rhs;
    rhs << X, 1;
    return S.partialPivLu().solve(rhs);
  }

  // Smallest index among cells containing X (min mu >= -tol), or -1.
  template <int dim>
  int brute_locate(const BoxMesh<dim> &mesh, const Eigen::VectorXd &u, const Point<dim> &X,
                   const double tol)
  {
    for (std::size_t o = 0; o < mesh.cells.size(); ++o)
      if (brute_barycentric<dim>(u, mesh.cells[o], X).minCoeff() >= -tol)
        return static_cast<int>(o);
    return -1;
  }

  template <int dim>
  Point<dim> reconstruct(const Eigen::VectorXd &u, const std::array<unsigned int, dim + 1> &cell,
                         const std::array<double, dim + 1> &mu)
  {
    Point<dim> X = Point<dim>::Zero();
    for (int b = 0; b <= dim; ++b)
      X += mu[b] * u.template segment<dim>(cell[b] * dim);
    return X;
  }

  template <int dim>
  void check_containment(const int n, const int n_points)
  {
    const BoxMesh<dim>    mesh = box_mesh<dim>(n);
    const Eigen::VectorXd u    = jitter(mesh, mesh.nodes, 0.2, 7);
    ASSERT_GT(min_measure(mesh, u), 0);
    const OldMeshLocator<dim> locator(mesh.cells, u);

    std::mt19937                           rng(3);
    std::uniform_real_distribution<double> d(0, 1);
    std::uniform_int_distribution<int>     pick(0, mesh.cells.size() - 1);
    for (int i = 0; i < n_points; ++i)
      {
        Point<dim> X;
        for (int k = 0; k < dim; ++k)
          X[k] = d(rng);
        const Location<dim> found = locator.locate(X);
        ASSERT_TRUE(found.inside);
        ASSERT_EQ(found.cell, brute_locate(mesh, u, X, locator.tolerance())) << "point " << i;
        const auto mu = brute_barycentric<dim>(u, mesh.cells[found.cell], X);
        for (int b = 0; b <= dim; ++b)
          {
            EXPECT_NEAR(found.barycentric[b], mu[b], 1e-12);
            EXPECT_GE(found.barycentric[b], -locator.tolerance());
          }
        EXPECT_LT((reconstruct<dim>(u, mesh.cells[found.cell], found.barycentric) - X).norm(), 1e-13);
        // The hinted path must agree, whatever the hint.
        EXPECT_EQ(locator.locate(X, pick(rng)).cell, found.cell);
        EXPECT_EQ(locator.locate(X, found.cell).cell, found.cell);
        EXPECT_EQ(locator.distance(found.cell, X), 0.0);
      }
  }

  // Points on shared faces, edges and vertices go to the smallest containing index.
  template <int dim>
  void check_shared_faces()
  {
    const BoxMesh<dim>        mesh = box_mesh<dim>(3);
    const OldMeshLocator<dim> locator(mesh.cells, mesh.nodes);
    std::mt19937              rng(5);
    std::uniform_real_distribution<double> d(0, 1);
    int n_shared = 0;
    for (std::size_t o = 0; o < mesh.cells.size(); ++o)
      for (int face = 0; face <= dim; ++face)
        {
          // A random point of the face opposite node `face` (and the face's vertices).
          std::array<double, dim + 1> w{};
          double                      sum = 0;
          for (int b = 0; b <= dim; ++b)
            if (b != face)
              sum += (w[b] = d(rng));
          Point<dim> X = Point<dim>::Zero();
          for (int b = 0; b <= dim; ++b)
            X += (w[b] / sum) * mesh.nodes.template segment<dim>(mesh.cells[o][b] * dim);
          const int expected = brute_locate(mesh, mesh.nodes, X, locator.tolerance());
          ASSERT_LE(expected, static_cast<int>(o));
          n_shared += expected < static_cast<int>(o);
          EXPECT_EQ(locator.locate(X).cell, expected);
          EXPECT_EQ(locator.locate(X, o).cell, expected);
        }
    EXPECT_GT(n_shared, 0);
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        const Point<dim> X = mesh.nodes.template segment<dim>(i * dim);
        EXPECT_EQ(locator.locate(X).cell, brute_locate(mesh, mesh.nodes, X, locator.tolerance()));
      }
  }

  // Outside the domain: the nearest cell (by distance, checked against brute force over all
  // cells and against sampling), with the barycentric coordinates of its extension.
  template <int dim>
  void check_outside()
  {
    const BoxMesh<dim>    mesh = box_mesh<dim>(4);
    const Eigen::VectorXd u    = jitter(mesh, mesh.nodes, 0.2, 11);
    const OldMeshLocator<dim> locator(mesh.cells, u);
    std::mt19937              rng(13);
    std::uniform_real_distribution<double> d(0, 1);
    std::uniform_int_distribution<int>     axis(0, dim - 1);
    for (int i = 0; i < 200; ++i)
      {
        // Slightly outside a random face of the box, at distance up to 0.2 spacing.
        Point<dim> X;
        for (int k = 0; k < dim; ++k)
          X[k] = d(rng);
        const int k  = axis(rng);
        const double offset = (1e-6 + 0.2 * d(rng)) * mesh.spacing();
        X[k]                 = d(rng) < 0.5 ? -offset : 1 + offset;

        const Location<dim> found = locator.locate(X);
        ASSERT_FALSE(found.inside);
        EXPECT_LT(*std::min_element(found.barycentric.begin(), found.barycentric.end()), 0.0);
        EXPECT_LT((reconstruct<dim>(u, mesh.cells[found.cell], found.barycentric) - X).norm(), 1e-12);
        const auto mu = brute_barycentric<dim>(u, mesh.cells[found.cell], X);
        for (int b = 0; b <= dim; ++b)
          EXPECT_NEAR(found.barycentric[b], mu[b], 1e-12);

        const double found_distance = locator.distance(found.cell, X);
        EXPECT_NEAR(found_distance, offset, 1e-12); // the box faces are kept by the jitter
        double best  = std::numeric_limits<double>::infinity();
        int    first = -1;
        for (std::size_t o = 0; o < mesh.cells.size(); ++o)
          {
            const double dist = locator.distance(o, X);
            if (dist < best - 1e-14)
              best = dist, first = o;
          }
        EXPECT_NEAR(found_distance, best, 1e-14);
        EXPECT_LE(found.cell, first);
        EXPECT_EQ(locator.locate(X, found.cell).cell, found.cell);
        EXPECT_EQ(locator.locate(X, i % mesh.cells.size()).cell, found.cell);
      }
  }

  // Face neighbours: symmetric, sharing the face's nodes; boundary faces have none.
  template <int dim>
  void check_neighbors(const int n)
  {
    const BoxMesh<dim>        mesh = box_mesh<dim>(n);
    const OldMeshLocator<dim> locator(mesh.cells, mesh.nodes);
    int                       n_boundary = 0;
    for (std::size_t o = 0; o < mesh.cells.size(); ++o)
      for (int f = 0; f <= dim; ++f)
        {
          const int other = locator.neighbor(o, f);
          if (other < 0)
            {
              ++n_boundary;
              continue;
            }
          ASSERT_NE(other, static_cast<int>(o));
          for (int a = 0; a <= dim; ++a)
            if (a != f)
              EXPECT_NE(std::find(mesh.cells[other].begin(), mesh.cells[other].end(), mesh.cells[o][a]),
                        mesh.cells[other].end());
          int back = 0;
          for (int g = 0; g <= dim; ++g)
            back += locator.neighbor(other, g) == static_cast<int>(o);
          EXPECT_EQ(back, 1);
        }
    // Boundary facets of the Kuhn box mesh: 2 dim faces with (dim-1)! n^(dim-1) facets each.
    EXPECT_EQ(n_boundary, static_cast<int>(2 * dim * factorial(dim - 1) * std::pow(n, dim - 1)));
  }

  // distance() against sampling: never larger than the distance to any point of the cell,
  // and within the sampling resolution of the closest sample.
  template <int dim>
  void check_distance()
  {
    const BoxMesh<dim>    mesh = box_mesh<dim>(2);
    const Eigen::VectorXd u    = jitter(mesh, mesh.nodes, 0.2, 17);
    const OldMeshLocator<dim> locator(mesh.cells, u);
    std::mt19937              rng(19);
    std::uniform_real_distribution<double> d(-1, 2);
    std::exponential_distribution<double>  e(1);
    const int o = mesh.cells.size() / 2;
    for (int i = 0; i < 30; ++i)
      {
        Point<dim> X;
        for (int k = 0; k < dim; ++k)
          X[k] = d(rng);
        double min_sample = std::numeric_limits<double>::infinity();
        for (int s = 0; s < 20000; ++s)
          {
            // Uniform barycentric samples (normalised exponentials), plus the vertices.
            std::array<double, dim + 1> w;
            double                      sum = 0;
            for (auto &wb : w)
              sum += (wb = e(rng));
            for (auto &wb : w)
              wb /= sum;
            if (s <= dim)
              for (int b = 0; b <= dim; ++b)
                w[b] = b == s ? 1 : 0;
            min_sample = std::min(min_sample, (reconstruct<dim>(u, mesh.cells[o], w) - X).norm());
          }
        const double dist = locator.distance(o, X);
        EXPECT_LE(dist, min_sample + 1e-14);
        EXPECT_GE(dist, min_sample - (dim == 3 ? 0.08 : 0.03) * mesh.spacing());
      }
  }
} // namespace

TEST(OldMeshLocator, Containment1D) { check_containment<1>(16, 2000); }
TEST(OldMeshLocator, Containment2D) { check_containment<2>(8, 2000); }
TEST(OldMeshLocator, Containment3D) { check_containment<3>(4, 2000); }

TEST(OldMeshLocator, SharedFaces1D) { check_shared_faces<1>(); }
TEST(OldMeshLocator, SharedFaces2D) { check_shared_faces<2>(); }
TEST(OldMeshLocator, SharedFaces3D) { check_shared_faces<3>(); }

TEST(OldMeshLocator, Outside1D) { check_outside<1>(); }
TEST(OldMeshLocator, Outside2D) { check_outside<2>(); }
TEST(OldMeshLocator, Outside3D) { check_outside<3>(); }

TEST(OldMeshLocator, Neighbors1D) { check_neighbors<1>(5); }
TEST(OldMeshLocator, Neighbors2D) { check_neighbors<2>(4); }
TEST(OldMeshLocator, Neighbors3D) { check_neighbors<3>(3); }

TEST(OldMeshLocator, Distance2D) { check_distance<2>(); }
TEST(OldMeshLocator, Distance3D) { check_distance<3>(); }

TEST(OldMeshLocator, NearestCellTieGoesToSmallestIndex)
{
  // A point beyond a boundary vertex shared by several cells is equally far from all of them.
  const BoxMesh<2>          mesh = box_mesh<2>(2);
  const OldMeshLocator<2>   locator(mesh.cells, mesh.nodes);
  const Eigen::Vector2d     X(0.5, -0.1); // below the boundary node (0.5, 0)
  int                       expected = -1;
  int                       n_ties   = 0;
  for (std::size_t o = 0; o < mesh.cells.size(); ++o)
    if (std::abs(locator.distance(o, X) - 0.1) < 1e-14)
      {
        ++n_ties;
        if (expected < 0)
          expected = o;
      }
  EXPECT_GE(n_ties, 2);
  EXPECT_EQ(locator.locate(X).cell, expected);
}

TEST(OldMeshLocator, RejectsDegenerateCells)
{
  BoxMesh<2>      mesh = box_mesh<2>(1);
  Eigen::VectorXd u    = mesh.nodes;
  u.segment<2>(mesh.cells[0][1] * 2) = u.segment<2>(mesh.cells[0][0] * 2);
  EXPECT_THROW((OldMeshLocator<2>(mesh.cells, u)), std::invalid_argument);
}
