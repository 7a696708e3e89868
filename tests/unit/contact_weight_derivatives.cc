// The barrier and friction weights are reference boundary measures, and friction's slip is
// measured from the material points' start positions phi_t(u): finite-difference checks of
// the contact energy's derivatives w.r.t. the reference positions u (gradient, Hessian) and
// of the mixed derivative w.r.t. deformed positions and u, in 2D and 3D; and the slip of a
// reference mesh moved under a body at rest.
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
    const Eigen::VectorXd u_start = mesh.reference;

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
    for (Eigen::Index i = 0; i < n_body; ++i)  // and sheared the body a little
      z_start[i] += 0.003 * std::sin(7.0 * i);
    StepContext<dim> context;
    context.u_start = u_start;
    context.z_start = z_start;
    terms.begin_step(context);
    // The derivatives are checked on a moved mesh whose nodes lie inside old cells (or, on
    // the boundary, outside the old domain): at the old nodes the origins phi_t(u) have kinks.
    Eigen::VectorXd u = u_start;
    for (Eigen::Index i = 0; i < u.size(); ++i)
      u[i] += 1e-3 * std::cos(3.0 * i + 1.0);
    terms.set_reference(u);
    friction.lag(z, terms.candidates_at(z), barrier.stiffness());
    const test_support::TermProbe<dim> probe{terms};
    ASSERT_GT(probe.objective(z, u), 0.0);
    // Friction is part of what is checked: it adds energy on top of the barrier.
    frictionless.set_reference(u);
    ASSERT_GT(probe.objective(z, u), frictionless.objective(z, frictionless.candidates_at(z)) * (1 + 1e-6));

    const auto d = probe.derivatives(z, u);
    // The collision mesh is shared: every evaluation sets its reference through the sum.
    const auto value_at = [&](const Eigen::VectorXd &v) { return probe.objective(z, v); };
    EXPECT_LT(test_support::relative_error(d.gu, test_support::fd_gradient(value_at, u, 1e-6)), 1e-6);
    EXPECT_LT(test_support::relative_error(probe.reference_gradient(z, u), d.gu), 1e-12);  // the first-order path
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

  // A body at rest on the ground whose reference mesh is translated by delta along the
  // ground: every material point at a node came from delta further on, so the friction is
  // that of the body slid back by delta on the unmoved mesh, not zero.
  template <int dim>
  void check_material_slip()
  {
    const double     dhat = 0.05;
    SimplexMesh<dim> mesh = test_support::small_box_mesh<dim>(2, 0.05, 3);
    Vec<dim>         origin = Vec<dim>::Zero(), up = Vec<dim>::Zero();
    up[1]                   = 1;
    std::vector<contact::RigidObstacle<dim>> obstacles{contact::make_plane<dim>(origin, up, 10.0)};
    CollisionMesh<dim>                       collisions(mesh, obstacles, dhat, true);
    TermSum<dim>                             terms(mesh, &collisions);
    auto &barrier  = terms.template add<ContactBarrierTerm<dim>>(collisions);
    auto &friction = terms.template add<FrictionTerm<dim>>(collisions, 0.4, 1e-3);
    barrier.set_stiffness(10.0);

    const Eigen::Index n_body = mesh.reference.size();
    Eigen::VectorXd    z(n_body + obstacles[0].rest_vertices.size() * dim);
    z.head(n_body) = mesh.reference;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      z[i * dim + 1] += 0.01;  // hovering within dhat of the ground
    for (std::size_t v = 0; v < obstacles[0].rest_vertices.size(); ++v)
      z.template segment<dim>(n_body + v * dim) = obstacles[0].rest_vertices[v];
    StepContext<dim> context;
    context.u_start = mesh.reference;
    context.z_start = z;
    terms.begin_step(context);
    terms.set_reference(context.u_start);
    friction.lag(z, terms.candidates_at(z), barrier.stiffness());

    // Without slip the mollified f0 is at its floor f0(0) = eps / 3.
    const double at_rest = friction.value(TermPoint{z, context.u_start, CollisionCandidates{}});

    const double    delta = 4e-3;  // above the mollifier's 1e-3: friction at full strength
    Eigen::VectorXd moved = context.u_start, slid_back = z;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        moved[i * dim] += delta;
        slid_back[i * dim] -= delta;
      }
    terms.set_reference(moved);
    const double moved_mesh = friction.value(TermPoint{z, moved, CollisionCandidates{}});
    terms.set_reference(context.u_start);
    const double slid_body = friction.value(TermPoint{slid_back, context.u_start, CollisionCandidates{}});
    EXPECT_GT(slid_body, 5 * at_rest);
    EXPECT_NEAR(moved_mesh, slid_body, 1e-12 * slid_body);
    // The force opposes the slip: pulling the body along delta on the moved mesh undoes it.
    Eigen::VectorXd g = Eigen::VectorXd::Zero(z.size());
    terms.set_reference(moved);
    friction.add_gradient(TermPoint{z, moved, CollisionCandidates{}}, g);
    double along = 0;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      along += g[i * dim];
    EXPECT_LT(along, 0.0);
  }
} // namespace

TEST(ContactWeightDerivatives, BarrierAndFriction2D) { check_weight_derivatives<2>(); }
TEST(ContactWeightDerivatives, BarrierAndFriction3D) { check_weight_derivatives<3>(); }
TEST(ContactWeightDerivatives, FrictionSlipOfMaterialPoints2D) { check_material_slip<2>(); }
TEST(ContactWeightDerivatives, FrictionSlipOfMaterialPoints3D) { check_material_slip<3>(); }
