// The first-order outer solve (Adaptivity/hessian = quasi-newton, and reduced-first after its
// first outer iteration) on one dynamic step of a free square with a non-uniform velocity
// (prm/verification/ritr/square_step_2d.prm) and of the paper's Fig. 9 rod
// (prm/ritr_rod_1d.prm):
//  - the reduced gradient it takes, the partial derivative of R in u at the solved state, is
//    the derivative of u -> R(x(u), u) with x(u) = argmin E(., u): finite differences of R
//    with every perturbed mesh's state solved tightly;
//  - run to a tight epsilon r it ends at the R of the exact reduced Hessian's trust region
//    (and on the rod at its mesh, which ritr_optimality_1d checks against brute force).
#include <ritr/adaptivity/ritr_solver.h>
#include <ritr/time/stepper.h>

#include "ritr_scenes.h"
#include "finite_difference.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace ritr;

namespace
{
  template <int dim>
  struct OneStep
  {
    explicit OneStep(const std::string &scene_file)
      : scene(read_scene(test_support::source_dir() + scene_file))
    {
      scene.end_time                = scene.time_step;
      scene.solver.newton_tolerance = 1e-9;
      problem                       = make_problem<dim>(scene);
      inner.emplace(*problem->terms, *problem->materials, problem->kinematic, implicit_step_settings(*problem, {}));
      step.step      = 1;
      step.time      = scene.time_step;
      step.time_step = scene.time_step;
      step.u_start = step.z_start = problem->initial_reference;
      step.v_start                = problem->initial_velocity;
      step.targets                = problem->targets(scene.time_step);
    }

    // One r-ITR step with the given outer Hessian, run to epsilon r alone.
    typename RitrSolver<dim>::Result solve(const RitrHessian hessian)
    {
      RitrSettings settings       = ritr_settings(*problem);
      settings.hessian            = hessian;
      settings.decrease_tolerance   = 0;
      settings.max_outer_iterations = 1000;
      RitrSolver<dim> solver(*problem->materials, *inner, settings, problem->transfer_quadrature());
      return solver.step(step);
    }

    Scene                               scene;
    std::unique_ptr<Problem<dim>>       problem;
    std::optional<ImplicitStep<dim>>    inner;
    StepContext<dim>                    step;
  };

  // dR/du at the step's solved start against central differences of u -> min_x R(x, u).
  template <int dim>
  void check_reduced_gradient(const std::string &scene_file)
  {
    OneStep<dim>    one(scene_file);
    TermSum<dim>   &terms = *one.problem->terms;
    Eigen::VectorXd z     = one.step.z_start;
    one.inner->solve_start_of_step(one.step, z);
    const Eigen::VectorXd &u = one.step.u_start;
    terms.set_reference(u);
    const Eigen::VectorXd gradient = terms.reference_gradient(z, terms.candidates_at(z));

    const auto reduced_objective = [&](const Eigen::VectorXd &w) {
      Eigen::VectorXd state = z;
      one.inner->solve_on_mesh(w, state, one.step.targets);
      terms.set_reference(w);
      return terms.objective(state, terms.candidates_at(state));
    };
    const Eigen::VectorXd differences = test_support::fd_gradient(reduced_objective, u, 1e-6);
    const double          error       = test_support::relative_error(gradient, differences);
    std::cout << scene_file << ": |dR/du| " << gradient.norm() << ", relative error against differences " << error
              << std::endl;
    EXPECT_GT(gradient.norm(), 0.0);
    EXPECT_LT(error, 1e-5);
  }

  // `first_order` (quasi-newton, or reduced-first: the exact Hessian for the first outer
  // iteration only) against the exact reduced Hessian's trust region.
  template <int dim>
  void check_same_minimum(const std::string &scene_file, const RitrHessian first_order)
  {
    OneStep<dim> one(scene_file);
    const auto   reduced = one.solve(RitrHessian::reduced);
    const auto   other   = one.solve(first_order);
    const double moved   = (reduced.u - one.step.u_start).template lpNorm<Eigen::Infinity>();
    const double apart   = (other.u - reduced.u).template lpNorm<Eigen::Infinity>();
    std::cout.precision(12);
    std::cout << scene_file << ": R from " << reduced.initial_objective << " to " << reduced.objective << " (reduced, "
              << reduced.outer_iterations << " outer iterations), " << other.objective << " ("
              << name_of(ritr_hessian_names, first_order) << ", " << other.outer_iterations << "); the meshes "
              << apart << " apart, the reduced one moved by " << moved << std::endl;
    // Converged, or no region small enough gave a decrease: R is flat to round-off there.
    EXPECT_NE(other.stop, OuterStop::iteration_limit);
    EXPECT_NE(other.stop, OuterStop::small_decrease);
    // The mesh moves: the comparison is not of two unmoved meshes.
    EXPECT_GT(moved, 1e-3);
    EXPECT_NEAR(other.objective, reduced.objective, 1e-10 * std::abs(reduced.objective));
    // R is flat along the square's valley of minima, where the meshes may differ by more than
    // epsilon r (R the same to 12 digits, nodes 6e-4 apart); the rod's minimum is a point.
    EXPECT_LT(apart, (dim == 1 ? 1e-4 : 1e-2) * moved);
  }
} // namespace

TEST(RitrQuasiNewton, ReducedGradientMatchesDifferencesOfRInTheSquare)
{
  check_reduced_gradient<2>("/prm/verification/ritr/square_step_2d.prm");
}

TEST(RitrQuasiNewton, ReducedGradientMatchesDifferencesOfROnTheRod) { check_reduced_gradient<1>("/prm/ritr_rod_1d.prm"); }

TEST(RitrQuasiNewton, ReachesTheReducedSolveInTheSquare)
{
  check_same_minimum<2>("/prm/verification/ritr/square_step_2d.prm", RitrHessian::quasi_newton);
}

TEST(RitrQuasiNewton, ReachesTheReducedSolveOnTheRod)
{
  check_same_minimum<1>("/prm/ritr_rod_1d.prm", RitrHessian::quasi_newton);
}

TEST(RitrQuasiNewton, ReducedFirstReachesTheReducedSolveInTheSquare)
{
  check_same_minimum<2>("/prm/verification/ritr/square_step_2d.prm", RitrHessian::reduced_first);
}

TEST(RitrQuasiNewton, ReducedFirstReachesTheReducedSolveOnTheRod)
{
  check_same_minimum<1>("/prm/ritr_rod_1d.prm", RitrHessian::reduced_first);
}
