// Parallel assembly: gradient and projected Hessian of the cell terms (elasticity, inertia,
// gravity) on a 2D mesh of about 100K vertices with 1 and with 2 threads, best of three,
// measured in one run.
#include <ritr/mesh/mesh_builder.h>
#include <ritr/terms/body_force_term.h>
#include <ritr/terms/elasticity_term.h>
#include <ritr/terms/inertia_term.h>
#include <ritr/terms/term_sum.h>

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <chrono>

using namespace ritr;

namespace
{
  double best_assembly_seconds(TermSum<2> &terms, const Eigen::VectorXd &x, const int threads)
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    double              best = 1e30;
    for (int r = 0; r < 3; ++r)
      {
        const auto      start = std::chrono::steady_clock::now();
        Eigen::VectorXd g     = Eigen::VectorXd::Zero(x.size());
        terms.add_energy_gradient(x, {}, g);
        MatrixAssembly<2> h(terms.mesh().cells);
        terms.add_energy_hessian(x, {}, true, h);
        const Triplets triplets = h.to_triplets();
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
    return best;
  }
} // namespace

TEST(AssemblyThreads, SpeedUpWithTwoThreads)
{
  BodyDescription body;
  body.shape        = "rectangle";
  body.upper        = {2, 1};
  body.subdivisions = {448, 224};
  const auto    mesh = build_mesh<2>({body});
  const CellMaterials<2> materials(mesh, {Material{}});
  TermSum<2>             terms(mesh, nullptr);
  terms.add<ElasticityTerm<2>>(materials);
  terms.add<InertiaTerm<2>>(materials, InertiaTerm<2>::Predictor::nodal, InertiaForm::corrected);
  terms.add<BodyForceTerm<2>>(materials);
  StepContext<2> step;
  step.time_step  = 0.01;
  step.gravity[1] = -9.81;
  step.u_start = step.z_start = mesh.reference;
  step.v_start                = Eigen::VectorXd::Zero(mesh.reference.size());
  terms.begin_step(step);
  terms.set_reference(mesh.reference);
  Eigen::VectorXd x = mesh.reference;
  for (Eigen::Index i = 0; i < x.size(); i += 2)
    x[i] *= 1.0 + 0.1 * x[i + 1];  // a non-trivial (sheared) state
  const double one = best_assembly_seconds(terms, x, 1);
  const double two = best_assembly_seconds(terms, x, 2);
  std::cout << "| vertices | 1 thread [s] | 2 threads [s] | speed-up |\n| " << mesh.n_nodes() << " | " << one << " | "
            << two << " | " << one / two << " |" << std::endl;
  EXPECT_GT(one / two, 1.2);
}
