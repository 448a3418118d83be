#include "uampc/mpc/ua_mpc_controller.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <type_traits>

#include "uampc/mpc/uncertainty_surrogate.hpp"

namespace uampc::mpc {

namespace {
using Clock = std::chrono::steady_clock;  // measures compute time only; never the sim clock

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}
}  // namespace

const char* modeName(Mode mode) {
  switch (mode) {
    case Mode::kUaMpc:
      return "ua_mpc";
    case Mode::kConstant:
      return "constant";
    case Mode::kZero:
      return "zero";
  }
  return "unknown";
}

Mode parseMode(const std::string& name) {
  for (Mode mode : {Mode::kUaMpc, Mode::kConstant, Mode::kZero}) {
    if (name == modeName(mode)) return mode;
  }
  throw std::invalid_argument("unknown mpc mode '" + name + "'; expected one of: ua_mpc, constant, zero");
}

UaMpcController::UaMpcController() : UaMpcController(Config{}) {}

namespace {
UaMpcController::Config withRangeWeighting(UaMpcController::Config config) {
  if (config.range_weight_voxel > 0.0) {
    config.uncertainty.range_weight_saturation = UncertaintyModel::rangeWeightSaturation(
        config.range_weight_voxel, config.lidar_points_per_frame, config.uncertainty.field_of_view);
  }
  return config;
}
}  // namespace

UaMpcController::UaMpcController(const Config& config)
    : config_(withRangeWeighting(config)),
      sample_count_(UncertaintySurrogate::samplesPerTurn(config.sample_step)),
      depth_map_(config.depth_map),
      normals_(config.normals),
      uncertainty_(config_.uncertainty),
      filter_(config.u_filter_weight),
      mpc_(config.mpc) {}

UaMpcController::Decision UaMpcController::step(const Eigen::Isometry3d& T_WB,
                                                const std::vector<Eigen::Vector3d>& local_map_W, double theta_now) {
  return stepWith(T_WB, local_map_W, theta_now);
}

UaMpcController::Decision UaMpcController::stepFloat(const Eigen::Isometry3d& T_WB,
                                                const std::vector<Eigen::Vector3f>& local_map_W, double theta_now) {
  return stepWith(T_WB, local_map_W, theta_now);
}

template <class Point>
UaMpcController::Decision UaMpcController::stepWith(const Eigen::Isometry3d& T_WB,
                                                    const std::vector<Point>& local_map_W, double theta_now) {
  const Clock::time_point start = Clock::now();
  Decision decision;
  decision.mode = config_.mode;
  decision.sample_start = theta_now;
  decision.sample_step = UncertaintySurrogate::turnStep(sample_count_);

  switch (config_.mode) {
    case Mode::kUaMpc:
      decision.omega = std::clamp(config_.mpc.omega_pre, config_.mpc.omega_min,
                                  config_.mpc.omega_max);  // fallback if nothing is seen
      break;
    case Mode::kConstant:
      decision.omega = config_.constant_speed;
      break;
    case Mode::kZero:
      decision.omega = 0.0;
      break;
  }
  const bool want_samples = config_.mode == Mode::kUaMpc || config_.profile_in_baselines;

  if (want_samples) {
    Clock::time_point t = Clock::now();
    if constexpr (std::is_same_v<Point, Eigen::Vector3f>) {
      depth_map_.renderFloat(local_map_W, T_WB);
    } else {
      depth_map_.render(local_map_W, T_WB);
    }
    decision.timings.depth_map_ms = millisecondsSince(t);
    decision.local_map_empty = depth_map_.occupiedCount() == 0;

    if (!decision.local_map_empty) {
      t = Clock::now();
      normals_.reset(depth_map_);
      decision.samples = filter_.apply(
          theta_now, decision.sample_step,
          uncertainty_.sample(depth_map_, normals_, theta_now, decision.sample_step, sample_count_));
      decision.timings.uncertainty_ms = millisecondsSince(t);

      if (config_.mode == Mode::kUaMpc) {
        t = Clock::now();
        const UncertaintySurrogate surrogate(theta_now, decision.sample_step, decision.samples);
        decision.plan = mpc_.solve(surrogate, theta_now, last_command_);
        decision.omega = decision.plan.speeds.front();
        decision.timings.solve_ms = millisecondsSince(t);
      }
    }
  } else {
    decision.local_map_empty = local_map_W.empty();
  }
  last_command_ = decision.omega;
  decision.timings.total_ms = millisecondsSince(start);
  return decision;
}

}  // namespace uampc::mpc
