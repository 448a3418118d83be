#include "simulated_lidar.hpp"

#include <algorithm>
#include <cmath>

namespace uampc::tools {

world::WorldSettings worldSettingsFor(const std::string& source) {
  world::WorldSettings settings;
  if (source == "corridor" || source == "multilevel" || source == "campus") {
    settings.world = source;
    return settings;
  }
  settings.world = "around_trajectory";
  settings.trajectory = "file";
  settings.trajectory_file = source;
  settings.interpolation = "smooth";
  settings.smoothing = 0.5;
  return settings;
}

frames::MotorAngleTrack constantSpeedMotor(double speed, double from, double to, double theta0) {
  frames::MotorAngleTrack motor(1e9);
  const double step = 0.005;
  for (long i = std::lround(std::floor(from / step)); i * step <= to + step; ++i) {
    const double t = i * step;
    motor.add({t, theta0 + speed * t, speed});
  }
  return motor;
}

lo::Scan toOdometryScan(const raycaster::Scan& cast) {
  lo::Scan scan;
  scan.stamp = cast.stamp;
  scan.points_L.reserve(cast.points.size());
  scan.time_offsets.reserve(cast.points.size());
  for (const auto& p : cast.points) {
    scan.points_L.push_back(p.position);
    scan.time_offsets.push_back(p.time_offset);
  }
  return scan;
}

double scanEndTime(const lo::Scan& scan) {
  double last = 0.0;
  for (float offset : scan.time_offsets) last = std::max(last, double(offset));
  return scan.stamp + last;
}

void startAtTruth(lo::OdometryConfig& config, const world::Trajectory& truth, double time) {
  const double h = 0.01;
  config.initial_pose = truth.poseAt(time);
  const Eigen::Isometry3d before = truth.poseAt(time - h);
  config.initial_velocity_W = (config.initial_pose.translation() - before.translation()) / h;
  const Eigen::AngleAxisd turn(before.linear().transpose() * config.initial_pose.linear());
  config.initial_angular_velocity_B = turn.axis() * turn.angle() / h;
}

double rotationAngle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

}  // namespace uampc::tools
