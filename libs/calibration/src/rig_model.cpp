#include "uampc/calibration/rig_model.hpp"

#include <Eigen/Geometry>

namespace uampc::calibration {

ObservableRig observablePart(const frames::MotorLidarCalibration& c) {
  const Eigen::Vector3d rpy = frames::rollPitchYawFromRotation(c.R_ML);
  ObservableRig x;
  x.rotation[0] = rpy.x();
  x.rotation[1] = rpy.y();
  x.offset[0] = c.r_ML.x();
  x.offset[1] = c.r_ML.y();
  x.time_offset[0] = c.time_offset;
  return x;
}

GaugeRig gaugePart(const frames::MotorLidarCalibration& c) {
  GaugeRig g;
  g.yaw = frames::rollPitchYawFromRotation(c.R_ML).z();
  g.z = c.r_ML.z();
  g.encoder_offset = c.encoder_offset;
  g.linearised_at = c.time_offset;
  return g;
}

ObservableRig truthInGaugeOf(const frames::MotorLidarCalibration& truth,
                             const frames::MotorLidarCalibration& believed) {
  ObservableRig x = observablePart(truth);
  const double turn = gaugePart(believed).yaw - gaugePart(truth).yaw;
  const Eigen::Vector2d offset = Eigen::Rotation2Dd(turn) * Eigen::Vector2d(truth.r_ML.x(), truth.r_ML.y());
  x.offset[0] = offset.x();
  x.offset[1] = offset.y();
  return x;
}

frames::MotorLidarCalibration assemble(const ObservableRig& x, const GaugeRig& gauge) {
  frames::MotorLidarCalibration c;
  c.R_ML = frames::rotationFromRollPitchYaw({x.rotation[0], x.rotation[1], gauge.yaw});
  c.r_ML = {x.offset[0], x.offset[1], gauge.z};
  c.encoder_offset = gauge.encoder_offset;
  c.time_offset = x.time_offset[0];
  return c;
}

void takeEncoderAnglesAt(double time_offset, const frames::MotorAngleTrack& encoder,
                         std::vector<CalibrationPoint>& points, GaugeRig& gauge) {
  std::size_t cursor = 0;
  for (auto& p : points) {
    const double t = p.time + time_offset;
    const auto theta = encoder.thetaAt(t, cursor);
    const auto omega = encoder.omegaAt(t);
    if (!theta || !omega) continue;
    p.encoder_theta = *theta;
    p.omega = *omega;
  }
  gauge.linearised_at = time_offset;
}

}  // namespace uampc::calibration
