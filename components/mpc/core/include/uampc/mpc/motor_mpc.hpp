// The motor-speed MPC of UA-MPC (docs/dev/architecture.md section 1), solved with Ceres on the
// surrogate U'.
//
// The paper optimises Omega_j = {omega_i, i = j-M .. j+M} under theta_{i+1} = theta_i + omega_i dt,
//
//   F = alpha * sum_i U'(theta_i)^2 + beta * sum_i (omega_i - omega_pre)^2.
//
// Our reading: the M past speeds omega_{j-M} .. omega_{j-1} have already been applied. They are
// constants, and so are their beta terms and the U' terms of the angles they produced; their only
// effect on the future is theta_j, which the encoder measures directly. They therefore drop out of
// the minimisation and are not an input here. The variables are the M + 1 future speeds
// omega_j .. omega_{j+M}; starting from the measured theta_j = theta_now, they produce the angles
// theta_{j+1} .. theta_{j+M+1}, and the minimised cost is
//
//   F = alpha * sum_{i=j+1}^{j+M+1} U'(theta_i)^2 + beta * sum_{i=j}^{j+M} (omega_i - omega_pre)^2.
//
// Weight convention: alpha and beta are used as they are. The residuals are sqrt(alpha) U'(theta_i)
// and sqrt(beta) (omega_i - omega_pre), so the sum of squared residuals is exactly F above. (The
// published reference code multiplies its residuals by the weights, which squares them: its
// alpha = 1000 is our alpha = 1e6.)
//
// Beyond the paper, off by default: a rate term gamma * sum_{i=j}^{j+M} (omega_i - omega_{i-1})^2,
// omega_{j-1} the previous command, ties each speed to the one before it. Nothing in the paper's F
// does, so with the piecewise-linear U' the minimum jumps between kinks and bounds from one step to
// the next (docs/results/point-map-regime.md, "The chatter"). Its residuals are
// sqrt(gamma) (omega_i - omega_{i-1}); without a previous command the first is left out.
//
// The Jacobian is analytic through the surrogate's slope (Eq. 10): d theta_i / d omega_l = dt for
// l < i, so d r_i / d omega_l = sqrt(alpha) dU'/dtheta(theta_i) dt. The solve starts at omega_pre
// (clamped into the bounds), the bounds are Ceres parameter bounds, and only the first speed is
// meant to be executed (receding horizon).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "uampc/mpc/uncertainty_surrogate.hpp"

namespace uampc::mpc {

class MotorMpc {
 public:
  struct Config {
    int horizon = 10;           // M: M + 1 future speeds are optimised
    double dt = 0.1;            // s, one control step
    double alpha = 1000.0;      // weight of the uncertainty term (used as is, see above)
    double beta = 1.0;          // weight of the preferred-speed term (used as is)
    double rate_weight = 0.0;   // gamma, weight of the rate term (used as is); 0: the paper's F
    double omega_pre = 3.6;     // rad/s, preferred speed and initial guess
    double omega_min = 0.0;     // rad/s, lower speed bound
    double omega_max = 7.2;     // rad/s, upper speed bound
    int max_iterations = 50;    // Ceres iterations
  };

  struct Plan {
    std::vector<double> speeds;                 // omega_j .. omega_{j+M}; speeds[0] is the command
    std::vector<double> angles;                 // theta_{j+1} .. theta_{j+M+1}
    std::vector<double> predicted_uncertainty;  // U'(theta_{j+1}) .. U'(theta_{j+M+1})
    double initial_cost = 0.0;                  // F at the initial guess
    double cost = 0.0;                          // F at the solution
    int iterations = 0;                         // Ceres iterations
    bool converged = false;                     // Ceres reported convergence
  };

  // Throws std::invalid_argument on horizon < 0, dt <= 0, negative weights or omega_min >= omega_max.
  MotorMpc();  // default Config
  explicit MotorMpc(const Config& config);

  // previous_command: omega_{j-1}, the rate term's first reference (NaN: none, as at the start).
  static constexpr double kNoPreviousCommand = std::numeric_limits<double>::quiet_NaN();
  Plan solve(const UncertaintySurrogate& surrogate, double theta_now,
             double previous_command = kNoPreviousCommand) const;

  // F for given future speeds (size horizon + 1), as minimised by solve().
  double cost(const UncertaintySurrogate& surrogate, double theta_now, const Eigen::VectorXd& speeds,
              double previous_command = kNoPreviousCommand) const;

  // The residual vector [sqrt(alpha) U'(theta_{j+1..j+M+1}); sqrt(beta) (omega - omega_pre)],
  // followed by [sqrt(gamma) (omega_i - omega_{i-1})] when rate_weight > 0, and, if jacobian is
  // not null, its analytic Jacobian with respect to the speeds.
  Eigen::VectorXd residuals(const UncertaintySurrogate& surrogate, double theta_now,
                            const Eigen::VectorXd& speeds, Eigen::MatrixXd* jacobian = nullptr,
                            double previous_command = kNoPreviousCommand) const;
  int residualCount() const;

  int variableCount() const { return config_.horizon + 1; }
  const Config& config() const { return config_; }

 private:
  Config config_;
};

}  // namespace uampc::mpc
