// The stress and contact-pressure arrays of the outputs: von Mises stress of the Cauchy
// stress against small-strain closed forms, and nodal contact pressure of a uniform load.
#include <ritr/elasticity/stress.h>
#include <ritr/mesh/mesh_builder.h>
#include <ritr/metrics/mesh_metrics.h>

#include <test_meshes.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace ritr;

namespace
{
  Material linear_material()
  {
    Material m;
    m.model          = MaterialModel::linear;
    m.youngs_modulus = 2e5;
    m.poisson_ratio  = 0.3;
    return m;
  }

  template <int dim>
  SmallMatrix<dim, double> identity()
  {
    SmallMatrix<dim, double> F{};
    for (int i = 0; i < dim; ++i)
      F[i][i] = 1.0;
    return F;
  }

  constexpr double small = 1e-6;  // strain at which the small-strain closed forms hold
} // namespace

TEST(StressMeasures, NoStressAtRestOrUnderRotation)
{
  const Material neo_hookean;
  EXPECT_NEAR(von_mises(cauchy_stress<3>(neo_hookean, identity<3>())), 0.0, 1e-9);
  const double             c = std::cos(0.7), s = std::sin(0.7);
  SmallMatrix<2, double>   rotation{{{c, -s}, {s, c}}};
  EXPECT_NEAR(von_mises(cauchy_stress<2>(neo_hookean, rotation)), 0.0, 1e-9);
}

TEST(StressMeasures, UniaxialStressOfARod)
{
  const Material           m = linear_material();
  SmallMatrix<1, double>   F{{{1 + small}}};
  EXPECT_NEAR(von_mises(cauchy_stress<1>(m, F)), m.youngs_modulus * small, 1e-6 * m.youngs_modulus * small);
}

TEST(StressMeasures, PlaneStrainCountsTheOutOfPlaneStress)
{
  // Stretch along x with the thickness held: sigma_yy = sigma_zz = lambda e, so the von
  // Mises stress is |sigma_xx - sigma_yy| = 2 mu e (it would be (lambda + 2 mu) e without
  // sigma_zz).
  const Material m = linear_material();
  auto           F = identity<2>();
  F[0][0] += small;
  EXPECT_NEAR(von_mises(cauchy_stress<2>(m, F)), 2 * m.mu(2) * small, 1e-5 * m.mu(2) * small);
}

TEST(StressMeasures, SimpleShear)
{
  const Material m = linear_material();
  auto           F = identity<3>();
  F[0][1]          = small;
  EXPECT_NEAR(von_mises(cauchy_stress<3>(m, F)), std::sqrt(3.0) * m.mu(3) * small, 1e-5 * m.mu(3) * small);
}

TEST(ContactPressure, UniformLoadOnTheBottomOfARectangle)
{
  BodyDescription body;
  body.lower        = {0, 0};
  body.upper        = {2, 1};
  body.subdivisions = {4, 2};
  const auto mesh   = build_mesh<2>({body});
  // A pressure p on the bottom edge: interior bottom nodes carry p times their share of it
  // (one edge length, 0.5), pushing up into the body.
  const double    p = 3.0;
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(2 * mesh.n_nodes());
  for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
    if (mesh.reference[2 * n + 1] == 0.0)
      forces[2 * n + 1] = p * 0.5;
  const Eigen::VectorXd pressure = nodal_contact_pressures(mesh, mesh.reference, forces);
  unsigned int          checked  = 0;
  for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
    {
      const double x = mesh.reference[2 * n], y = mesh.reference[2 * n + 1];
      if (y == 0.0 && x > 0.0 && x < 2.0)
        {
          EXPECT_NEAR(pressure[n], p, 1e-12) << "node at x = " << x;
          ++checked;
        }
      else if (y > 0.0)
        EXPECT_EQ(pressure[n], 0.0);
    }
  EXPECT_EQ(checked, 3u);
}

TEST(ContactPressure, RodEndsCarryTheForce)
{
  const auto      mesh   = test_support::small_box_mesh<1>(4, 0.0);  // the rod [0, 1]
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(mesh.n_nodes());
  for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
    forces[n] = mesh.reference[n] == 0.0 ? 5.0 : 0.0;
  const Eigen::VectorXd pressure = nodal_contact_pressures(mesh, mesh.reference, forces);
  for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
    EXPECT_EQ(pressure[n], mesh.reference[n] == 0.0 ? 5.0 : 0.0);
}
