// The barrier and friction weights are reference boundary measures: finite-difference
// checks of the contact energy's derivatives w.r.t. the reference positions u (gradient,
// Hessian) and of the mixed derivative w.r.t. deformed positions and u, in 2D and 3D.
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/terms/friction_term.h>

#include <gtest/gtest.h>

#include "term_probe.h"
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

    // The contact terms alone, with and without friction.
    CollisionMesh<dim> collisions(mesh, obstacles, dhat, true);
    TermSum<dim>       terms(mesh, &collisions), frictionless(mesh, &collisions);
    auto              &barrier  = terms.template add<ContactBarrierTerm<dim>>(collisions);
    auto              &friction = terms.template add<FrictionTerm<dim>>(collisions, 0.4, 1e-3);
    barrier.set_stiffness(10.0);
    frictionless.template add<ContactBarrierTerm<dim>>(collisions).set_stiffness(10.0);
    const Eigen::VectorXd u = mesh.reference;
    terms.set_reference(u);

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
    friction.lag(z, terms.candidates_at(z), z_start, barrier.stiffness());
    const test_support::TermProbe<dim> probe{terms};
    ASSERT_GT(probe.objective(z, u), 0.0);
    // Friction is part of what is checked: it adds energy on top of the barrier.
    frictionless.set_reference(u);
    ASSERT_GT(probe.objective(z, u), frictionless.objective(z, frictionless.candidates_at(z)) * (1 + 1e-6));

    const auto d = probe.derivatives(z, u);
    // The collision mesh is shared: every evaluation sets its reference through the sum.
    const auto value_at = [&](const Eigen::VectorXd &v) { return probe.objective(z, v); };
    EXPECT_LT(test_support::relative_error(d.gu, test_support::fd_gradient(value_at, u, 1e-6)), 1e-6);
    const auto gu_at = [&](const Eigen::VectorXd &v) { return Eigen::VectorXd(probe.derivatives(z, v).gu); };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.huu, u.size(), u.size()),
                                           test_support::fd_jacobian(gu_at, u, 1e-6)),
              1e-5);
    const auto gx_at = [&](const Eigen::VectorXd &v) { return probe.gradient(z, v); };
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxu, z.size(), u.size()),
                                           test_support::fd_jacobian(gx_at, u, 1e-6)),
              1e-5);
    // The coupling blocks' state parts are the state derivatives (H_zz projected per stencil).
    EXPECT_LT(test_support::relative_error(d.gx, probe.gradient(z, u)), 1e-12);
    EXPECT_LT(test_support::relative_error(test_support::dense(d.hxx, z.size(), z.size()), probe.hessian(z, u, true)),
              1e-12);
    // The trust-region Newton's one-pass Hessians, barrier and friction.
    probe.expect_one_pass_hessians_match(z, u);
  }
} // namespace

TEST(ContactWeightDerivatives, BarrierAndFriction2D) { check_weight_derivatives<2>(); }
TEST(ContactWeightDerivatives, BarrierAndFriction3D) { check_weight_derivatives<3>(); }
