#include "uampc/adapters/rig_parameters.hpp"

#include <cmath>
#include <stdexcept>

namespace uampc::adapters {

void declareRigParameters(ComponentSpec& spec) {
  spec.param("tilt_deg", 30.0, "LiDAR tilt about its own x axis on the motor, degrees (reference rig: 30)")
      .between(-180.0, 180.0)
      .partOfRig();
  spec.param("lidar_rotation_rpy_deg", std::vector<double>{},
             "LiDAR rotation on the motor (R_ML) as roll, pitch, yaw about the motor's fixed x, y, z axes, "
             "R = Rz(yaw) Ry(pitch) Rx(roll), degrees; empty: tilt_deg about x (give one of the two)")
      .ofLength(3)
      .between(-180.0, 180.0)
      .partOfRig()
      .notWith("tilt_deg");
  spec.param("lidar_offset", std::vector<double>{0.0, 0.0, 0.0}, "LiDAR origin in the motor frame (r_ML), m")
      .ofLength(3)
      .partOfRig();
  spec.param("encoder_offset_deg", 0.0,
             "the encoder's zero: it reads the rotor's angle theta of Eq. 1 plus this, degrees")
      .between(-180.0, 180.0)
      .partOfRig();
  spec.param("time_offset", 0.0,
             "LiDAR-to-encoder clock offset: a point stamped t was measured when the encoder's clock read "
             "t + time_offset, s")
      .between(-1.0, 1.0)
      .partOfRig();
  spec.param("imu_offset", std::vector<double>{0.0, 0.0, 0.0},
             "the IMU's origin in the LiDAR frame, its axes the LiDAR's, m (the Livox Mid-360's: "
             "[0.011, 0.02329, -0.04412]); used by the LiDAR-inertial LO and the simulated IMU")
      .ofLength(3)
      .between(-1.0, 1.0)
      .partOfRig();
}

void declareLidarModelParameters(ComponentSpec& spec) {
  std::vector<std::string> models = lidar::namedLidarModels();
  models.emplace_back("spinning");
  spec.param("lidar_model", "livox_mid360",
             "LiDAR model: one known by name, or spinning (any spinning LiDAR, the lidar_* parameters below)")
      .oneOf(models)
      .partOfRig();
  spec.param("lidar_elevations_deg", std::vector<double>{-15, -13, -11, -9, -7, -5, -3, -1, 1, 3, 5, 7, 9, 11, 13, 15},
             "lidar_model spinning: the beam elevations, degrees")
      .partOfRig();
  spec.param("lidar_points_per_second", 288000.0, "lidar_model spinning: points per second")
      .between(1.0, 1e8)
      .partOfRig();
  spec.param("lidar_frame_rate", 10.0, "lidar_model spinning: frames per second, Hz").between(0.1, 100.0).partOfRig();
  spec.param("lidar_min_range", 0.5, "lidar_model spinning: minimum range, m").between(0.0, 1000.0).partOfRig();
  spec.param("lidar_max_range", 100.0, "lidar_model spinning: maximum range, m").between(0.1, 10000.0).partOfRig();
}

// A frame's points are allocated at once (and again in the scan message and the LO): 1e8 points/s
// at 1 Hz, both within their bounds, needed more than 8 GB for one frame. Two million points is 7x a
// 128-beam LiDAR's frame.
constexpr double kMaxPointsPerFrame = 2e6;

lidar::LidarModel lidarModel(const Context& ctx) {
  const std::string name = ctx.paramString("lidar_model");
  if (name != "spinning") return lidar::lidarModelByName(name);
  const double per_frame = ctx.paramDouble("lidar_points_per_second") / ctx.paramDouble("lidar_frame_rate");
  if (per_frame > kMaxPointsPerFrame) {
    throw std::runtime_error("lidar_points_per_second / lidar_frame_rate = " + std::to_string(per_frame) +
                             " points per frame; at most " + std::to_string(static_cast<long>(kMaxPointsPerFrame)) +
                             " are simulated (memory)");
  }
  return lidar::spinningLidar(ctx.paramDoubleList("lidar_elevations_deg"), ctx.paramDouble("lidar_points_per_second"),
                              ctx.paramDouble("lidar_frame_rate"), ctx.paramDouble("lidar_min_range"),
                              ctx.paramDouble("lidar_max_range"));
}

Eigen::Vector3d degreesToRadians(const Eigen::Vector3d& degrees) { return degrees * (M_PI / 180.0); }

Eigen::Vector3d vector3Param(const Context& ctx, const std::string& name) {
  const auto v = ctx.paramDoubleList(name);
  if (v.size() != 3) throw std::runtime_error(name + " must have three values (x, y, z)");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

namespace {

// The calibration from the rig parameters, however they are looked up (a component's context, a
// scene's rig block).
template <typename Double, typename List>
frames::MotorLidarCalibration calibrationFrom(const Double& number, const List& list) {
  auto vector3 = [&](const std::string& name) {
    const auto v = list(name);
    if (v.size() != 3) throw std::runtime_error(name + " must have three values (x, y, z)");
    return Eigen::Vector3d(v[0], v[1], v[2]);
  };
  frames::MotorLidarCalibration c =
      frames::MotorLidarCalibration::tiltedAboutX(number("tilt_deg") * M_PI / 180.0, vector3("lidar_offset"));
  // Not given (the empty default): tilt_deg alone, computed as before so that every output stays
  // the same bit for bit.
  if (!list("lidar_rotation_rpy_deg").empty()) {
    c.R_ML = frames::rotationFromRollPitchYaw(degreesToRadians(vector3("lidar_rotation_rpy_deg")));
  }
  c.encoder_offset = number("encoder_offset_deg") * M_PI / 180.0;
  c.time_offset = number("time_offset");
  c.imu_position_L = vector3("imu_offset");
  return c;
}

}  // namespace

frames::MotorLidarCalibration rigCalibration(const Context& ctx) {
  return calibrationFrom([&](const std::string& name) { return ctx.paramDouble(name); },
                         [&](const std::string& name) { return ctx.paramDoubleList(name); });
}

frames::MotorLidarCalibration rigCalibration(const std::map<std::string, ParameterValue>& rig) {
  ComponentSpec spec;  // the declared defaults, for what the rig block leaves out
  declareRigParameters(spec);
  auto value = [&](const std::string& name) -> ParameterValue {
    if (const auto it = rig.find(name); it != rig.end()) return it->second;
    return *spec.findParameter(name)->default_value;
  };
  return calibrationFrom([&](const std::string& name) { return std::get<double>(value(name)); },
                         [&](const std::string& name) { return std::get<std::vector<double>>(value(name)); });
}

}  // namespace uampc::adapters
