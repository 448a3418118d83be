#include "uampc/lo/acceleration_unit.hpp"

#include <sstream>

namespace uampc::lo {

AccelerationUnitDetector::AccelerationUnitDetector(AccelerationUnit unit) {
  if (unit == AccelerationUnit::kMetresPerSecondSquared) {
    scale_ = 1.0;
    decision_ = "IMU acceleration read in m/s^2 (imu_acceleration_unit)";
  } else if (unit == AccelerationUnit::kStandardGravity) {
    scale_ = frames::kStandardGravity;
    decision_ = "IMU acceleration read in g and scaled by 9.80665 (imu_acceleration_unit)";
  }
}

bool AccelerationUnitDetector::observe(const Eigen::Vector3d& acceleration) {
  if (scale_) return true;
  magnitude_sum_ += acceleration.norm();
  if (++readings_ < kReadings) return false;
  decide(magnitude_sum_ / readings_);
  return true;
}

// Gravity within a factor of two either way: a mean between the two bands, or beyond both, is no
// IMU at rest or moving as rigs move, and is taken as sensor_msgs says, with a warning.
void AccelerationUnitDetector::decide(double mean_magnitude) {
  std::ostringstream why;
  why << "the first " << readings_ << " IMU readings' mean acceleration is " << mean_magnitude;
  if (mean_magnitude >= 0.5 && mean_magnitude <= 2.0) {
    scale_ = frames::kStandardGravity;
    why << ": read in g (as livox_ros_driver2 publishes it) and scaled by 9.80665";
  } else if (mean_magnitude >= 0.5 * frames::kStandardGravity && mean_magnitude <= 2.0 * frames::kStandardGravity) {
    scale_ = 1.0;
    why << ": read in m/s^2";
  } else {
    scale_ = 1.0;
    why << ", near neither 1 g nor 9.8 m/s^2: read in m/s^2 as sensor_msgs/Imu says; set lo.imu_acceleration_unit "
           "if that is wrong";
  }
  decision_ = why.str();
}

}  // namespace uampc::lo
