// Eq. 1's inner bracket with the calibration as unknowns, for a base standing still
// (docs/decisions/rig-calibration-gauge.md):
//
//   p_B = R_BM(theta_encoder(t + time_offset) - encoder_offset) ( R_ML p_L + r_ML )          (Eq. 1)
//   R_ML = Rz(yaw) Ry(pitch) Rx(roll),  r_ML = (x, y, z)
//
// From a still base only what changes the map's shape with the motor angle can be seen: roll and
// pitch (the motor axis in the LiDAR frame), x and y (the LiDAR's distance from the axis), and
// the clock offset when the motor's speed varies. Yaw and the encoder's zero turn the whole map
// about the motor axis, z shifts it along the axis: they are held at the believed values.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::calibration {

// A sampled LiDAR point with the encoder's reading at its time.
struct CalibrationPoint {
  Eigen::Vector3d p_L;
  double time = 0.0;           // s, the LiDAR's clock
  double encoder_theta = 0.0;  // rad, the encoder's angle at time + linearised_at (the clock offset)
  double omega = 0.0;          // rad/s, the motor's rate there
};

// The estimated values: roll and pitch (rad), x and y (m), the clock offset (s).
struct ObservableRig {
  double rotation[2] = {0.0, 0.0};  // roll, pitch
  double offset[2] = {0.0, 0.0};    // x, y
  double time_offset[1] = {0.0};
};

// The values held fixed (the gauge) and where the encoder angles were taken.
struct GaugeRig {
  double yaw = 0.0;             // rad
  double z = 0.0;               // m
  double encoder_offset = 0.0;  // rad
  double linearised_at = 0.0;   // s: the points' encoder_theta are at time + this
};

ObservableRig observablePart(const frames::MotorLidarCalibration& c);
GaugeRig gaugePart(const frames::MotorLidarCalibration& c);

// What an estimate held at `believed`'s gauge should find for a rig that truly is `truth`: its
// roll, pitch and clock offset, and its offset turned about the motor axis by the yaws'
// difference (the map a still base sees is the truth's turned by a constant about that axis).
ObservableRig truthInGaugeOf(const frames::MotorLidarCalibration& truth, const frames::MotorLidarCalibration& believed);
frames::MotorLidarCalibration assemble(const ObservableRig& x, const GaugeRig& gauge);

// Re-reads every point's encoder angle and rate at time + time_offset (from the track) and marks
// the gauge as linearised there. Points the track does not cover keep their values.
void takeEncoderAnglesAt(double time_offset, const frames::MotorAngleTrack& encoder,
                         std::vector<CalibrationPoint>& points, GaugeRig& gauge);

// R = Rz(yaw) Ry(pitch) Rx(roll) times v, for Ceres' Jets as for doubles.
template <typename T>
Eigen::Matrix<T, 3, 1> rotateRollPitchYaw(const T& roll, const T& pitch, double yaw, const Eigen::Matrix<T, 3, 1>& v) {
  using std::cos;
  using std::sin;
  const T cr = cos(roll), sr = sin(roll), cp = cos(pitch), sp = sin(pitch);
  const Eigen::Matrix<T, 3, 1> after_roll(v.x(), cr * v.y() - sr * v.z(), sr * v.y() + cr * v.z());
  const Eigen::Matrix<T, 3, 1> after_pitch(cp * after_roll.x() + sp * after_roll.z(), after_roll.y(),
                                           -sp * after_roll.x() + cp * after_roll.z());
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  return {cy * after_pitch.x() - sy * after_pitch.y(), sy * after_pitch.x() + cy * after_pitch.y(), after_pitch.z()};
}

// Eq. 1's inner bracket for one point with the candidate calibration: its place in the base frame.
template <typename T>
Eigen::Matrix<T, 3, 1> pointInBase(const CalibrationPoint& p, const T* rotation, const T* offset, const T* time_offset,
                                   const GaugeRig& gauge) {
  using std::cos;
  using std::sin;
  // The encoder's angle at t + time_offset, linear about where it was read (a clock offset of
  // milliseconds; re-read every outer iteration).
  const T theta = T(p.encoder_theta) + T(p.omega) * (time_offset[0] - T(gauge.linearised_at)) - T(gauge.encoder_offset);
  const Eigen::Matrix<T, 3, 1> p_M =
      rotateRollPitchYaw(rotation[0], rotation[1], gauge.yaw, Eigen::Matrix<T, 3, 1>(p.p_L.cast<T>())) +
      Eigen::Matrix<T, 3, 1>(offset[0], offset[1], T(gauge.z));
  const T c = cos(theta), s = sin(theta);
  return {c * p_M.x() - s * p_M.y(), s * p_M.x() + c * p_M.y(), p_M.z()};
}

// The rotor's angle of a point (for telling motor angles apart), rad.
inline double rotorAngle(const CalibrationPoint& p, const ObservableRig& x, const GaugeRig& gauge) {
  return p.encoder_theta + p.omega * (x.time_offset[0] - gauge.linearised_at) - gauge.encoder_offset;
}

}  // namespace uampc::calibration
