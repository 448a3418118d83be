// The unit of an IMU's acceleration. sensor_msgs/Imu says m/s^2; livox_ros_driver2 publishes the
// Mid-360's in g (docs/user/rig.md). `auto` tells them apart by the mean magnitude of the first
// readings: an IMU reads gravity, about 1 in g and 9.8 in m/s^2, and what a rig adds to it by
// moving does not carry a mean over its first quarter second from one to the other.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "uampc/frames/gravity.hpp"

namespace uampc::lo {

enum class AccelerationUnit { kAuto, kMetresPerSecondSquared, kStandardGravity };

class AccelerationUnitDetector {
 public:
  static constexpr int kReadings = 50;  // a quarter second at the Mid-360's 200 Hz

  explicit AccelerationUnitDetector(AccelerationUnit unit);

  // A reading's acceleration, as published (finite). Returns whether the scale is known.
  bool observe(const Eigen::Vector3d& acceleration);
  // m/s^2 per unit of the readings, once known: at once for a given unit, after kReadings with auto.
  std::optional<double> scale() const { return scale_; }
  // What was decided, and from what, for the log.
  const std::string& decision() const { return decision_; }

 private:
  void decide(double mean_magnitude);

  std::optional<double> scale_;
  std::string decision_;
  double magnitude_sum_ = 0.0;
  int readings_ = 0;
};

}  // namespace uampc::lo
