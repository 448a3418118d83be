// When a scan can be registered. Every point of a scan needs the motor angle at its own time
// (Eq. 1), so the odometry waits for encoder states covering the scan; the component queues scans
// until then.
#pragma once

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// The time of the scan's last point, s (its stamp when no point is later).
double scanEndTime(const Scan& scan);

// True when the encoder states cover the scan's points and imu_until (the newest IMU reading's
// time in LiDAR-inertial mode; +infinity in LiDAR-only mode) reaches its end, or when the encoder
// states have run on more than max_motor_wait seconds past its end: a gap in the encoder states
// delays the odometry, it does not stop it.
bool readyToRegister(const Scan& scan, const frames::MotorAngleTrack& motor, double imu_until, double max_motor_wait);

}  // namespace uampc::lo
