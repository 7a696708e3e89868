// Mesh generation: measures, outward boundary orientation (divergence theorem), boundary ids,
// several bodies, uniform refinement.
#include <ritr/mesh/mesh_builder.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

using namespace ritr;

namespace
{
  template <int dim>
  double total_measure(const SimplexMesh<dim> &mesh)
  {
    double s = 0;
    for (const auto &cell : mesh.cells)
      {
        const double m = simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell));
        EXPECT_GT(m, 0.0);
        s += m;
      }
    return s;
  }

  // int_boundary X . n dA = dim * volume when every facet is outward-oriented.
  template <int dim>
  double boundary_flux(const SimplexMesh<dim> &mesh)
  {
    double flux = 0;
    for (const auto &f : mesh.boundary_facets)
      {
        const Vec<dim> a = mesh.reference_node(f[0]);
        if constexpr (dim == 2)
          {
            const Vec<2> t = mesh.reference_node(f[1]) - a;
            flux += (a + 0.5 * t).dot(Vec<2>(t[1], -t[0]));
          }
        else if constexpr (dim == 3)
          {
            const Vec<3> b = mesh.reference_node(f[1]), c = mesh.reference_node(f[2]);
            flux += ((a + b + c) / 3).dot(0.5 * (b - a).cross(c - a));
          }
      }
    return flux;
  }
} // namespace

TEST(MeshBuilding, RectangleAndBox)
{
  BodyDescription r;
  r.shape        = "rectangle";
  r.lower        = {0, 0};
  r.upper        = {2, 1};
  r.subdivisions = {4, 2};
  const auto m2  = build_mesh<2>({r});
  EXPECT_NEAR(total_measure(m2), 2.0, 1e-12);
  EXPECT_NEAR(boundary_flux(m2), 2 * 2.0, 1e-12);
  EXPECT_EQ(m2.boundary_facets.size(), 12u);
  std::vector<int> per_id(4, 0);
  for (const unsigned id : m2.boundary_ids)
    per_id.at(id)++;
  EXPECT_EQ(per_id, (std::vector<int>{2, 2, 4, 4}));

  BodyDescription b;
  b.shape        = "box";
  b.upper        = {1, 2, 3};
  b.subdivisions = {2, 2, 2};
  const auto m3  = build_mesh<3>({b});
  EXPECT_NEAR(total_measure(m3), 6.0, 1e-12);
  EXPECT_NEAR(boundary_flux(m3), 3 * 6.0, 1e-10);
  const auto fine = refine_uniformly(m3);
  EXPECT_EQ(fine.n_cells(), 8 * m3.n_cells());
  EXPECT_NEAR(total_measure(fine), 6.0, 1e-12);
  EXPECT_NEAR(boundary_flux(fine), 3 * 6.0, 1e-10);
}

TEST(MeshBuilding, DiskBallAndSeveralBodies)
{
  BodyDescription disk;
  disk.shape             = "disk";
  disk.radius            = 0.5;
  disk.shape_refinements = 3;
  BodyDescription other  = disk;
  other.translation      = {2, 0};
  other.material_id      = 1;
  const auto mesh        = build_mesh<2>({disk, other});
  EXPECT_EQ(mesh.n_bodies(), 2u);
  EXPECT_NEAR(total_measure(mesh), 2 * M_PI * 0.25, 0.02);
  EXPECT_NEAR(boundary_flux(mesh), 2 * total_measure(mesh), 1e-10);
  EXPECT_EQ(mesh.cell_material.back(), 1u);
  // Refinement keeps which scene body each node came from.
  const auto fine = refine_uniformly(mesh);
  for (unsigned int i = 0; i < fine.n_nodes(); ++i)
    EXPECT_EQ(fine.node_part[i], fine.reference[2 * i] > 1.0 ? 1u : 0u);

  BodyDescription ball;
  ball.shape             = "ball";
  ball.shape_refinements = 1;
  const auto m3          = build_mesh<3>({ball});
  EXPECT_NEAR(boundary_flux(m3), 3 * total_measure(m3), 1e-10);
  EXPECT_GT(total_measure(m3), 0.7 * 4.0 / 3.0 * M_PI);
}

TEST(MeshBuilding, IntervalAndErrors)
{
  BodyDescription rod;
  rod.shape        = "interval";
  rod.lower        = {0};
  rod.upper        = {1};
  rod.subdivisions = {3};
  const auto m1    = build_mesh<1>({rod});
  EXPECT_EQ(m1.n_nodes(), 4u);
  EXPECT_EQ(m1.boundary_facets.size(), 2u);
  EXPECT_NEAR(total_measure(m1), 1.0, 1e-14);

  BodyDescription wrong;
  wrong.shape = "ball";
  EXPECT_THROW(build_mesh<2>({wrong}), std::runtime_error);
  wrong.shape = "file";
  wrong.file  = "does-not-exist.msh";
  EXPECT_THROW(build_mesh<2>({wrong}), std::runtime_error);
}

// Rods get the overlap check of triangles and tetrahedra: two cells on the same side of a
// node (a rod folded back, a segment given twice) are refused; cells in any node order and
// any listing order are not.
TEST(MeshBuilding, FoldedOrDoubledRodsAreRefused)
{
  const auto rod = [](const std::vector<double> &x, const std::vector<std::array<unsigned int, 2>> &cells) {
    SimplexMesh<1> mesh;
    mesh.reference = Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
    mesh.cells     = cells;
    compute_boundary_and_bodies(mesh);
    return mesh;
  };
  const auto straight = rod({0, 2, 1}, {{{2, 0}}, {{1, 2}}});
  EXPECT_EQ(straight.boundary_facets.size(), 2u);
  EXPECT_NEAR(total_measure(straight), 2.0, 1e-14);
  EXPECT_THROW(rod({0, 1, 0.5}, {{{0, 1}}, {{1, 2}}}), std::runtime_error);           // folded at node 1
  EXPECT_THROW(rod({0, 0.5, 1}, {{{0, 1}}, {{1, 2}}, {{2, 1}}}), std::runtime_error);  // segment twice
  EXPECT_THROW(rod({0, 1, 2, 1.5}, {{{0, 1}}, {{1, 2}}, {{1, 3}}}), std::runtime_error);  // branching
}
