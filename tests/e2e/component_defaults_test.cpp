// One source for every default: what the installed components declare (`uampc components
// --json`, the same declarations a scene is validated against) equals their cores' configs.
// Before, mpc's panorama was 180 x 90 in the component and 360 x 180 in the core, so the core's
// tests and benchmarks measured another setup than the scenes ran.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "command_runner.hpp"
#include "uampc/evaluator/completeness.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/motor/simulated_motor.hpp"
#include "uampc/mpc/ua_mpc_controller.hpp"
#include "uampc/raycaster/imu_simulator.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::test {
namespace {

// name -> default of one component type's parameters.
YAML::Node defaultsOf(const YAML::Node& components, const std::string& type) {
  YAML::Node defaults;
  for (const auto& c : components) {
    if (c["type"].as<std::string>() != type) continue;
    for (const auto& p : c["parameters"]) defaults[p["name"].as<std::string>()] = p["default"];
  }
  return defaults;
}

YAML::Node installedComponents() {
  const CommandResult r = runUampc("components --json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return YAML::Load(r.output);  // JSON is YAML
}

TEST(ComponentDefaults, MpcDeclaresItsCoresDefaults) {
  const YAML::Node mpc = defaultsOf(installedComponents(), "mpc");
  ASSERT_TRUE(mpc.size() > 0) << "no mpc component installed";
  const mpc::UaMpcController::Config core;
  const double deg = 180.0 / M_PI;
  EXPECT_EQ(mpc["mode"].as<std::string>(), mpc::modeName(core.mode));
  EXPECT_DOUBLE_EQ(mpc["constant_speed"].as<double>(), core.constant_speed);
  EXPECT_DOUBLE_EQ(mpc["alpha"].as<double>(), core.mpc.alpha);
  EXPECT_DOUBLE_EQ(mpc["beta"].as<double>(), core.mpc.beta);
  EXPECT_DOUBLE_EQ(mpc["omega_pre"].as<double>(), core.mpc.omega_pre);
  EXPECT_DOUBLE_EQ(mpc["omega_min"].as<double>(), core.mpc.omega_min);
  EXPECT_DOUBLE_EQ(mpc["omega_max"].as<double>(), core.mpc.omega_max);
  EXPECT_EQ(mpc["horizon"].as<int>(), core.mpc.horizon);
  EXPECT_DOUBLE_EQ(mpc["horizon_dt"].as<double>(), core.mpc.dt);
  EXPECT_NEAR(mpc["sample_step_deg"].as<double>(), core.sample_step * deg, 1e-9);
  EXPECT_NEAR(mpc["ray_step_deg"].as<double>(), core.uncertainty.azimuth_step * deg, 1e-9);
  EXPECT_EQ(mpc["panorama_width"].as<int>(), core.depth_map.width);
  EXPECT_EQ(mpc["panorama_height"].as<int>(), core.depth_map.height);
  EXPECT_DOUBLE_EQ(mpc["range_weight_voxel"].as<double>(), core.range_weight_voxel);
  EXPECT_DOUBLE_EQ(mpc["u_filter_weight"].as<double>(), core.u_filter_weight);
}

TEST(ComponentDefaults, LoDeclaresItsCoresDefaults) {
  const YAML::Node lo = defaultsOf(installedComponents(), "lo");
  ASSERT_TRUE(lo.size() > 0) << "no lo component installed";
  const lo::OdometryConfig core;
  EXPECT_DOUBLE_EQ(lo["scan_voxel_size"].as<double>(), core.scan_voxel_size);
  EXPECT_DOUBLE_EQ(lo["map_voxel_size"].as<double>(), core.map_voxel_size);
  EXPECT_DOUBLE_EQ(lo["map_radius"].as<double>(), core.map_radius);
  EXPECT_DOUBLE_EQ(lo["measurement_variance"].as<double>(), core.measurement_variance);
  EXPECT_DOUBLE_EQ(lo["linear_process_noise"].as<double>(), core.linear_process_noise);
  EXPECT_DOUBLE_EQ(lo["angular_process_noise"].as<double>(), core.angular_process_noise);
  EXPECT_EQ(lo["max_iterations"].as<int>(), core.max_iterations);
  EXPECT_EQ(lo["degeneracy_aware"].as<bool>(), core.degeneracy_aware);
  EXPECT_DOUBLE_EQ(lo["degeneracy_threshold"].as<double>(), core.degeneracy_threshold);
  EXPECT_DOUBLE_EQ(lo["max_linear_acceleration"].as<double>(), core.max_linear_acceleration);
  EXPECT_DOUBLE_EQ(lo["max_angular_acceleration"].as<double>(), core.max_angular_acceleration);
  EXPECT_DOUBLE_EQ(lo["lost_after"].as<double>(), core.lost_after);
  EXPECT_EQ(lo["use_imu"].as<bool>(), core.use_imu);
  EXPECT_DOUBLE_EQ(lo["min_range"].as<double>(), core.min_range);
  EXPECT_DOUBLE_EQ(lo["max_range"].as<double>(), core.max_range);
}

TEST(ComponentDefaults, MotorBridgeDeclaresItsCoresDefaults) {
  const YAML::Node motor = defaultsOf(installedComponents(), "motor_bridge");
  ASSERT_TRUE(motor.size() > 0) << "no motor_bridge component installed";
  const motor::MotorLimits core;
  EXPECT_DOUBLE_EQ(motor["max_speed"].as<double>(), core.max_speed);
  EXPECT_DOUBLE_EQ(motor["max_acceleration"].as<double>(), core.max_acceleration);
  EXPECT_DOUBLE_EQ(motor["time_constant"].as<double>(), core.time_constant);
  EXPECT_DOUBLE_EQ(motor["encoder_resolution"].as<double>(), core.encoder_resolution);
}

TEST(ComponentDefaults, RaycasterDeclaresItsCoresDefaults) {
  const YAML::Node raycaster = defaultsOf(installedComponents(), "raycaster");
  ASSERT_TRUE(raycaster.size() > 0) << "no raycaster component installed";
  const raycaster::RayCasterConfig scans;
  const raycaster::ImuSimulatorConfig imu;
  EXPECT_NEAR(raycaster["angular_noise_deg"].as<double>(), scans.angular_noise_stddev * 180.0 / M_PI, 1e-12);
  EXPECT_DOUBLE_EQ(raycaster["dropout"].as<double>(), scans.dropout_probability);
  EXPECT_DOUBLE_EQ(raycaster["imu_rate"].as<double>(), imu.rate_hz);
  EXPECT_DOUBLE_EQ(raycaster["gyro_noise_density"].as<double>(), imu.noise.gyro_noise_density);
  EXPECT_DOUBLE_EQ(raycaster["gyro_random_walk"].as<double>(), imu.noise.gyro_random_walk);
  EXPECT_DOUBLE_EQ(raycaster["accel_noise_density"].as<double>(), imu.noise.accel_noise_density);
  EXPECT_DOUBLE_EQ(raycaster["accel_random_walk"].as<double>(), imu.noise.accel_random_walk);
  // Deliberately not the core's (exact casts, range_noise_stddev 0): the default model's datasheet.
  EXPECT_DOUBLE_EQ(raycaster["range_noise"].as<double>(), lidar::livoxMid360().range_precision);
}

TEST(ComponentDefaults, EvaluatorDeclaresItsCoresDefaults) {
  const YAML::Node evaluator = defaultsOf(installedComponents(), "evaluator");
  ASSERT_TRUE(evaluator.size() > 0) << "no evaluator component installed";
  const evaluator::CompletenessConfig core;
  EXPECT_DOUBLE_EQ(evaluator["voxel_size"].as<double>(), core.voxel_size);
  EXPECT_DOUBLE_EQ(evaluator["window"].as<double>(), core.window_duration);
  // grid_offset is deliberately not the core's 0 (see evaluator_component.cpp).
}

TEST(ComponentDefaults, MapProviderDeclaresItsCoresDefaults) {
  const YAML::Node map = defaultsOf(installedComponents(), "map_provider");
  ASSERT_TRUE(map.size() > 0) << "no map_provider component installed";
  const world::WorldSettings core;
  EXPECT_EQ(map["world"].as<std::string>(), core.world);
  EXPECT_EQ(map["map_file"].as<std::string>(), core.map_file);
  EXPECT_DOUBLE_EQ(map["map_voxel_size"].as<double>(), core.map_voxel_size);
  ASSERT_EQ(map["map_offset"].size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(map["map_offset"][i].as<double>(), core.map_offset[i]);
  EXPECT_EQ(map["trajectory"].as<std::string>(), core.trajectory);
  EXPECT_EQ(map["trajectory_file"].as<std::string>(), core.trajectory_file);
  EXPECT_EQ(map["attitude"].as<std::string>(), core.attitude);
  EXPECT_EQ(map["interpolation"].as<std::string>(), core.interpolation);
  EXPECT_DOUBLE_EQ(map["smoothing"].as<double>(), core.smoothing);
  EXPECT_DOUBLE_EQ(map["trajectory_start"].as<double>(), core.trajectory_start);
  EXPECT_DOUBLE_EQ(map["path_speed"].as<double>(), core.path_speed);
  EXPECT_EQ(map["path_laps"].as<int>(), core.path_laps);
  EXPECT_DOUBLE_EQ(map["base_height"].as<double>(), core.base_height);
  EXPECT_EQ(map["campus_poor_rows"].as<int>(), core.campus_poor_rows);
  EXPECT_DOUBLE_EQ(map["corridor_door_spacing"].as<double>(), core.corridor_door_spacing);
  EXPECT_EQ(map["density_profile"].as<std::string>(), core.density_profile);
  EXPECT_DOUBLE_EQ(map["open_fraction"].as<double>(), core.open_fraction);
}

}  // namespace
}  // namespace uampc::test
