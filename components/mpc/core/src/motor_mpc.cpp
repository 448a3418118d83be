// The only translation unit that includes Ceres.
#include "uampc/mpc/motor_mpc.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace uampc::mpc {

namespace {

int residualCountOf(const MotorMpc::Config& config) {
  return (config.rate_weight > 0.0 ? 3 : 2) * (config.horizon + 1);
}

// The rate term's rows, after the paper's 2n: sqrt(gamma) (omega_i - omega_{i-1}), the first
// against the previous command (0, with no Jacobian, when there is none).
void evaluateRates(const MotorMpc::Config& config, double previous_command, const double* speeds,
                   double* residuals, double* jacobian) {
  const int n = config.horizon + 1;
  const double sqrt_gamma = std::sqrt(config.rate_weight);
  for (int i = 0; i < n; ++i) {
    const int row = 2 * n + i;
    const bool has_before = i > 0 || std::isfinite(previous_command);
    const double before = i > 0 ? speeds[i - 1] : previous_command;
    residuals[row] = has_before ? sqrt_gamma * (speeds[i] - before) : 0.0;
    if (jacobian == nullptr || !has_before) continue;
    jacobian[row * n + i] = sqrt_gamma;
    if (i > 0) jacobian[row * n + i - 1] = -sqrt_gamma;
  }
}

// Residuals and row-major Jacobian of the horizon (see the header), shared by Ceres and the API.
void evaluateHorizon(const MotorMpc::Config& config, const UncertaintySurrogate& surrogate,
                     double theta_now, double previous_command, const double* speeds, double* residuals,
                     double* jacobian) {
  const int n = config.horizon + 1;
  const double sqrt_alpha = std::sqrt(config.alpha);
  const double sqrt_beta = std::sqrt(config.beta);
  if (jacobian != nullptr) std::fill(jacobian, jacobian + residualCountOf(config) * n, 0.0);
  double theta = theta_now;
  for (int i = 0; i < n; ++i) {
    theta += speeds[i] * config.dt;  // motor model: theta_{i+1} = theta_i + omega_i dt
    double u = 0.0;
    double slope = 0.0;
    surrogate.evaluate(theta, &u, &slope);  // Eqs. 9 and 10
    residuals[i] = sqrt_alpha * u;
    residuals[n + i] = sqrt_beta * (speeds[i] - config.omega_pre);
    if (jacobian != nullptr) {
      // theta_{j+1+i} depends on omega_j .. omega_{j+i}, each with d theta / d omega = dt.
      const double d = sqrt_alpha * slope * config.dt;
      for (int l = 0; l <= i; ++l) jacobian[i * n + l] = d;
      jacobian[(n + i) * n + i] = sqrt_beta;
    }
  }
  if (config.rate_weight > 0.0) evaluateRates(config, previous_command, speeds, residuals, jacobian);
}

class HorizonCost final : public ceres::CostFunction {
 public:
  HorizonCost(const MotorMpc::Config& config, const UncertaintySurrogate& surrogate, double theta_now,
              double previous_command)
      : config_(config), surrogate_(surrogate), theta_now_(theta_now), previous_command_(previous_command) {
    set_num_residuals(residualCountOf(config));
    mutable_parameter_block_sizes()->push_back(config.horizon + 1);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    double* jacobian = (jacobians != nullptr) ? jacobians[0] : nullptr;
    evaluateHorizon(config_, surrogate_, theta_now_, previous_command_, parameters[0], residuals, jacobian);
    return true;
  }

 private:
  const MotorMpc::Config& config_;
  const UncertaintySurrogate& surrogate_;
  double theta_now_;
  double previous_command_;
};

}  // namespace

MotorMpc::MotorMpc() : MotorMpc(Config{}) {}

MotorMpc::MotorMpc(const Config& config) : config_(config) {
  if (config_.horizon < 0) throw std::invalid_argument("MotorMpc: horizon must be >= 0");
  if (!(config_.dt > 0.0)) throw std::invalid_argument("MotorMpc: dt must be > 0");
  if (!(config_.alpha >= 0.0) || !(config_.beta >= 0.0) || !(config_.rate_weight >= 0.0)) {
    throw std::invalid_argument("MotorMpc: alpha, beta and rate_weight must be >= 0");
  }
  if (!(config_.omega_min < config_.omega_max)) {
    throw std::invalid_argument("MotorMpc: need omega_min < omega_max");
  }
  if (config_.max_iterations < 1) {
    throw std::invalid_argument("MotorMpc: max_iterations must be >= 1");
  }
}

int MotorMpc::residualCount() const { return residualCountOf(config_); }

Eigen::VectorXd MotorMpc::residuals(const UncertaintySurrogate& surrogate, double theta_now,
                                    const Eigen::VectorXd& speeds, Eigen::MatrixXd* jacobian,
                                    double previous_command) const {
  const int n = variableCount();
  if (speeds.size() != n) throw std::invalid_argument("MotorMpc: need horizon + 1 speeds");
  Eigen::VectorXd r(residualCount());
  if (jacobian == nullptr) {
    evaluateHorizon(config_, surrogate, theta_now, previous_command, speeds.data(), r.data(), nullptr);
    return r;
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(residualCount(), n);
  evaluateHorizon(config_, surrogate, theta_now, previous_command, speeds.data(), r.data(), J.data());
  *jacobian = J;
  return r;
}

double MotorMpc::cost(const UncertaintySurrogate& surrogate, double theta_now, const Eigen::VectorXd& speeds,
                      double previous_command) const {
  return residuals(surrogate, theta_now, speeds, nullptr, previous_command).squaredNorm();
}

MotorMpc::Plan MotorMpc::solve(const UncertaintySurrogate& surrogate, double theta_now,
                               double previous_command) const {
  const int n = variableCount();
  const double start = std::clamp(config_.omega_pre, config_.omega_min, config_.omega_max);
  Eigen::VectorXd speeds = Eigen::VectorXd::Constant(n, start);

  Plan plan;
  plan.initial_cost = cost(surrogate, theta_now, speeds, previous_command);

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);  // owns the cost function
  problem.AddResidualBlock(new HorizonCost(config_, surrogate, theta_now, previous_command), nullptr,
                           speeds.data());
  for (int i = 0; i < n; ++i) {
    problem.SetParameterLowerBound(speeds.data(), i, config_.omega_min);
    problem.SetParameterUpperBound(speeds.data(), i, config_.omega_max);
  }

  ceres::Solver::Options options;
  // M + 1 = 11 variables: the damped 11 x 11 normal equations of Levenberg-Marquardt are positive
  // definite and factor faster than a QR of the 22 x 11 Jacobian, with the same steps up to
  // rounding (mpc_bench scene: same iterations, speeds within 1e-12 rad/s of DENSE_QR).
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.max_num_iterations = config_.max_iterations;
  // U' is piecewise linear, so the cost has kinks where Gauss-Newton steps overshoot and the trust
  // region has to shrink towards the kink; Ceres' default tolerances stop too early there. The
  // problem is tiny (M + 1 variables), so tight tolerances cost microseconds.
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  plan.speeds.assign(speeds.data(), speeds.data() + n);
  plan.cost = cost(surrogate, theta_now, speeds, previous_command);  // = 2 * summary.final_cost (Ceres halves)
  plan.iterations = static_cast<int>(summary.iterations.size());
  plan.converged = summary.termination_type == ceres::CONVERGENCE;
  double theta = theta_now;
  for (int i = 0; i < n; ++i) {
    theta += speeds[i] * config_.dt;
    plan.angles.push_back(theta);
    plan.predicted_uncertainty.push_back(surrogate.value(theta));
  }
  return plan;
}

}  // namespace uampc::mpc
