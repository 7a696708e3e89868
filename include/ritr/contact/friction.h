#pragma once
// Lagged IPC friction (Li et al. 2020).
//
// From the contact constraints evaluated at lagged positions V_lag, each constraint k
// gets a fixed normal force magnitude lambda_k, tangent basis T_k (dim x (dim-1)) and
// closest-point coefficients c_k (relative position r = sum_i c_i x_i of the two closest
// points). With the step displacement dV = V - V_start (obstacle vertices included,
// they move by script), u_k = T_k^T sum_i c_i dx_i and the dissipative potential is
//
//   D(V) = sum_k mu_k lambda_k f0(|u_k|),
//
// f0 the IPC C1 mollification of |u| with f0' = f1, f1(y) = 2y/eps - y^2/eps^2 for
// y < eps = epsilon_v_times_h, 1 above.
//
// In 1D there is no tangent direction: friction is identically zero (no friction
// constraints are built; energy, gradient and Hessian vanish).
#include <ritr/contact/constraints.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace ritr::contact
{
  // Friction mollifier and its derivative-based quantities (eps = epsilon_v * h).
  double friction_f0(double y, double eps);
  double friction_f1(double y, double eps);
  // f1(y) / y, finite at y = 0 (2 / eps).
  double friction_f1_over_y(double y, double eps);
  // (f1'(y) y - f1(y)) / y^3, the coefficient of u u^T in the Hessian of f0(|u|); finite
  // limits are used at y = 0 where it multiplies u u^T = 0.
  double friction_f2_term(double y, double eps);

  template <int dim>
  struct FrictionConstraint
  {
    // Vertices with non-zero coefficient (at most 4) and their coefficients.
    std::array<int, 4>    vertices     = {{-1, -1, -1, -1}};
    std::array<double, 4> coefficients = {{0.0, 0.0, 0.0, 0.0}};
    int                   n_vertices   = 0;

    // Orthonormal tangent basis (dim x (dim-1); one unused column in 1D).
    Eigen::Matrix<double, dim, (dim > 1 ? dim - 1 : 1)> basis =
      Eigen::Matrix<double, dim, (dim > 1 ? dim - 1 : 1)>::Zero();

    double normal_force = 0.0; // lambda_k = -kappa w m db/d(unsquared distance)
    double mu           = 0.0; // friction coefficient
  };

  // Builds the lagged friction data at V_lag with friction coefficient mu.
  // lambda_k = -kappa w_k m_k(V_lag) db/dd * 2 sqrt(d), the magnitude of the barrier force
  // along the contact normal (for edge-edge including the mollifier value m_k, so nearly
  // parallel edges whose barrier is switched off carry no friction either). Empty in 1D.
  template <int dim>
  std::vector<FrictionConstraint<dim>>
  build_friction_constraints(const std::vector<Constraint> &constraints,
                             const Eigen::MatrixXd &V_lag, double dhat, double kappa,
                             const ConstraintWeights &weights, double mu);

  template <int dim>
  double friction_energy(const std::vector<FrictionConstraint<dim>> &friction,
                         const Eigen::MatrixXd &V, const Eigen::MatrixXd &V_start,
                         double epsilon_v_times_h);

  template <int dim>
  Eigen::VectorXd friction_gradient(const std::vector<FrictionConstraint<dim>> &friction,
                                    const Eigen::MatrixXd &V, const Eigen::MatrixXd &V_start,
                                    double epsilon_v_times_h);

  // Hessian of D. Per constraint it is mu lambda (c c^T) (x) (T M T^T) with the
  // (dim-1)x(dim-1) matrix M = f1/y I + f2 u u^T. M is PSD analytically for this f1;
  // project_psd clamps its eigenvalues at zero anyway so that round-off can never make
  // the assembled Hessian indefinite.
  template <int dim>
  Triplets
  friction_hessian(const std::vector<FrictionConstraint<dim>> &friction,
                   const Eigen::MatrixXd &V, const Eigen::MatrixXd &V_start,
                   double epsilon_v_times_h, bool project_psd = true);
  // Both at once: the exact Hessian and the projected one, entry for entry in the same order.
  template <int dim>
  std::pair<Triplets, Triplets>
  friction_hessian_and_projection(const std::vector<FrictionConstraint<dim>> &friction, const Eigen::MatrixXd &V,
                                  const Eigen::MatrixXd &V_start, double epsilon_v_times_h);
} // namespace ritr::contact
