#pragma once
// IPC log barrier on squared distances, the edge-edge mollifier and the adaptive barrier
// stiffness rules of Li et al. 2020 (IPC, supplementary Sec. on barrier stiffness).
//
// All distances d here are SQUARED distances and dhat_sqr = dhat^2, which avoids square
// roots in every kernel; the barrier itself is common/log_barrier.h applied to d.
#include <ritr/common/log_barrier.h>

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace ritr::contact
{
  // IPC's edge-edge mollifier threshold eps_x = 1e-3 |ea0 - ea1|^2 |eb0 - eb1|^2, meant
  // to be evaluated at REST positions.
  inline double edge_edge_mollifier_threshold(const Eigen::Vector3d &ea0,
                                              const Eigen::Vector3d &ea1,
                                              const Eigen::Vector3d &eb0,
                                              const Eigen::Vector3d &eb1)
  {
    return 1e-3 * (ea0 - ea1).squaredNorm() * (eb0 - eb1).squaredNorm();
  }

  // Mollifier m(c) of c = |ea x eb|^2: (c/eps_x)(2 - c/eps_x) below eps_x, 1 above. It
  // smoothly switches the edge-edge barrier off as the edges become parallel, where the
  // line-line distance is not smooth.
  inline double edge_edge_mollifier(const double c, const double eps_x)
  {
    if (c >= eps_x)
      return 1.0;
    const double s = c / eps_x;
    return s * (2.0 - s);
  }
  inline double edge_edge_mollifier_first_derivative(const double c, const double eps_x)
  {
    if (c >= eps_x)
      return 0.0;
    return 2.0 / eps_x - 2.0 * c / (eps_x * eps_x);
  }
  inline double edge_edge_mollifier_second_derivative(const double c, const double eps_x)
  {
    if (c >= eps_x)
      return 0.0;
    return -2.0 / (eps_x * eps_x);
  }

  // Diagonal of the axis-aligned bounding box of the rows of V (0 for an empty V).
  double bbox_diagonal(const Eigen::MatrixXd &V);

  struct BarrierStiffness
  {
    double kappa     = 0.0; // stiffness to use
    double kappa_min = 0.0; // lower bound from the mass scale
    double kappa_max = 0.0; // upper bound for later doubling (100 kappa_min)
  };

  // Initial barrier stiffness (IPC).
  //  bbox_diagonal:  diagonal l of the scene bounding box;
  //  dhat:           unsquared activation distance;
  //  average_mass:   average lumped nodal mass m;
  //  average_weight: average constraint weight w of the bodies' collision vertices (1 for
  //                  IPC's unweighted barrier);
  //  grad_energy:    gradient of the incremental potential without contact, at the start
  //                  of the time step;
  //  grad_barrier:   gradient of the unscaled weighted barrier sum at the same positions
  //                  (barrier_gradient, i.e. before multiplying by kappa).
  // kappa_min = 1e11 m / (4 w d_ref b''(d_ref)) with d_ref = (1e-8 l)^2 (clamped to
  // dhat^2/2), i.e. the stiffness at which one typical constraint's normal Hessian at a tiny
  // gap matches 1e11 times the mass; kappa_max = 100 kappa_min. IPC's bounds are meant for
  // unit weights: with weights that are boundary measures (~h^(dim-1)) and no division by w,
  // the cap held 3D gaps at 1e-4 dhat, where the barrier's quadratic model is good over a
  // fraction of the gap only and CCD cut most Newton steps to a few percent (doc/method.md,
  // Barrier stiffness). kappa is the minimiser of |grad_energy + kappa grad_barrier|, clamped
  // to [kappa_min, kappa_max] (kappa_min when there is no barrier gradient).
  BarrierStiffness initial_barrier_stiffness(double bbox_diagonal, double dhat,
                                             double average_mass, double average_weight,
                                             const Eigen::VectorXd &grad_energy,
                                             const Eigen::VectorXd &grad_barrier);

  // Adaptive stiffness update (IPC), called after each Newton iteration with the minimum
  // UNSQUARED distances of the previous and current iterates. Returns min(2 kappa,
  // kappa_max) if both distances are below epsilon_scale * bbox_diagonal and the distance
  // decreased (contact is being squeezed), otherwise kappa unchanged.
  double update_barrier_stiffness(double previous_min_distance, double min_distance,
                                  double kappa, double kappa_max, double bbox_diagonal,
                                  double epsilon_scale = 1e-9);
} // namespace ritr::contact
