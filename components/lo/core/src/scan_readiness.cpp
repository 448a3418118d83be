#include "uampc/lo/scan_readiness.hpp"

#include <algorithm>

namespace uampc::lo {

double scanEndTime(const Scan& scan) {
  double end = scan.stamp;
  for (float t : scan.time_offsets) end = std::max(end, scan.stamp + t);
  return end;
}

bool readyToRegister(const Scan& scan, const frames::MotorAngleTrack& motor, double imu_until, double max_motor_wait) {
  const double end = scanEndTime(scan);
  const bool covered = motor.covers(scan.stamp, end) && imu_until >= end;
  const bool waited = !motor.empty() && motor.newest().time > end + max_motor_wait;
  return covered || waited;
}

}  // namespace uampc::lo
