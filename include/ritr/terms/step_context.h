#pragma once
// Everything one time (or load) step starts from, fixed before any solve of the step: the
// step's size and end time, the load, the start-of-step mesh, state and velocity, and where
// the prescribed entries must be at the end. The terms read it in begin_step(); nothing
// changes it afterwards.
#include <Eigen/Core>

#include <array>

namespace ritr
{
  template <int dim>
  struct StepContext
  {
    unsigned int            step      = 0;  // 1 for the first step
    double                  time      = 0;  // at the end of the step
    double                  time_step = 0;  // h (dynamics) or the load step (statics)
    bool                    dynamic   = true;
    std::array<double, dim> gravity{};  // body force per unit mass at `time`, load factor applied
    Eigen::VectorXd         u_start;    // reference positions of the body nodes
    Eigen::VectorXd         z_start;    // state: [body node positions, obstacle vertices]
    Eigen::VectorXd         v_start;    // body node velocities
    Eigen::VectorXd         targets;    // prescribed state entries at the end of the step
    // The contact barrier's stiffness the previous step ended with (0 before the first step):
    // a step starts at least as stiff, so that the gaps the last step opened stay open.
    double                  barrier_stiffness = 0;

    Eigen::VectorXd x_start() const { return z_start.head(u_start.size()); }
    // Implicit Euler's predictor x_t + h v_t on the start-of-step mesh.
    Eigen::VectorXd predictor() const { return x_start() + time_step * v_start; }
    // The weight of the potential energies against inertia: h^2 in dynamics (paper eq. 6),
    // 1 in statics, where there is no inertia.
    double potential_weight() const { return dynamic ? time_step * time_step : 1.0; }
  };
} // namespace ritr
