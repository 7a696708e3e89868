// The barrier and friction weights are reference boundary measures: finite-difference
// checks of the contact energy's derivatives w.r.t. the reference positions u (gradient,
// Hessian) and of the mixed derivative w.r.t. deformed positions and u, in 2D and 3D.
#include <ritr/contact/contact_potential.h>

#include <gtest/gtest.h>

#include "finite_difference.h"
#include "test_meshes.h"

using namespace ritr;

namespace
{
  template <int dim>
  void check_weight_derivatives()
  {
    const double dhat = 0.05;
    SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2, 0.05, 3);
    // The body hovers just above the ground plane y = 0, closer than dhat.
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      mesh.reference[i * dim + 1] += 0.02;
    Vec<dim> origin = Vec<dim>::Zero(), up = Vec<dim>::Zero();
    up[1]           = 1;
    std::vector<contact::RigidObstacle<dim>> obstacles{contact::make_plane<dim>(origin, up, 10.0)};

    ContactSettings settings;
    settings.dhat                 = dhat;
    settings.friction_coefficient = 0.4;
    settings.epsilon_v_times_h    = 1e-3;
    ContactPotential<dim> contact(mesh, obstacles, settings);
    contact.set_stiffness(10.0);

    // State: deformed body (lowered a bit, sheared) and the ground's vertices.
    const Eigen::Index n_body = mesh.reference.size();
    Eigen::VectorXd    z(n_body + obstacles[0].rest_vertices.size() * dim);
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      for (int k = 0; k < dim; ++k)
        z[i * dim + k] = mesh.reference[i * dim + k] + (k == 0 ? 0.01 * mesh.reference[i * dim + 1] : 0.0) -
                         (k == 1 ? 0.005 : 0.0);
    for (std::size_t v = 0; v < obstacles[0].rest_vertices.size(); ++v)
      z.template segment<dim>(n_body + v * dim) = obstacles[0].rest_vertices[v];
    Eigen::VectorXd z_start = z;
    z_start.head(n_body).array() -= 0.002;  // the step slid every body node
    const CollisionCandidates candidates = contact.candidates_at(z);
    contact.update_friction(z, candidates, z_start);
    ASSERT_GT(contact.value(z, candidates), 0.0);
    // Friction is part of what is checked: it adds energy on top of the barrier.
    settings.friction_coefficient = 0.0;
    ContactPotential<dim> frictionless(mesh, obstacles, settings);
    frictionless.set_stiffness(10.0);
    ASSERT_GT(contact.value(z, candidates), frictionless.value(z, candidates) * (1 + 1e-6));

    const Eigen::VectorXd u = mesh.reference;
    typename ContactPotential<dim>::ReferenceDerivatives d;
    contact.reference_derivatives(z, candidates, d);

    const auto value_at = [&](const Eigen::VectorXd &v) {
      contact.set_reference(v);
      const double e = contact.value(z, candidates);
      contact.set_reference(u);
      return e;
    };
    EXPECT_LT(test_support::relative_error(d.gu, test_support::fd_gradient(value_at, u, 1e-6)), 1e-6);

    const auto gu_at = [&](const Eigen::VectorXd &v) {
      contact.set_reference(v);
      typename ContactPotential<dim>::ReferenceDerivatives r;
      contact.reference_derivatives(z, candidates, r);
      contact.set_reference(u);
      return r.gu;
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.huu, u.size(), u.size()), test_support::fd_jacobian(gu_at, u, 1e-6)),
              1e-5);

    const auto gx_at = [&](const Eigen::VectorXd &v) {
      contact.set_reference(v);
      Eigen::VectorXd g = Eigen::VectorXd::Zero(z.size());
      contact.add_gradient(z, candidates, g);
      contact.set_reference(u);
      return g;
    };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxu, z.size(), u.size()), test_support::fd_jacobian(gx_at, u, 1e-6)),
              1e-5);
  }
} // namespace

TEST(ContactWeightDerivatives, BarrierAndFriction2D) { check_weight_derivatives<2>(); }
TEST(ContactWeightDerivatives, BarrierAndFriction3D) { check_weight_derivatives<3>(); }
