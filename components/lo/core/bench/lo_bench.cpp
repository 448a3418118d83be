// Cost of one 20k-point Mid-360-like frame on one core, and the size of the local map over a long
// run. Scans are simulated beforehand (synthetic_world.hpp); only registerScan is timed.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "../test/synthetic_world.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"

namespace uampc::lo {
namespace {

struct Recording {
  std::vector<Scan> scans;
  frames::MotorAngleTrack motor{1e9};  // keeps every reading: the whole run is pre-recorded
  sim::Trajectory truth;
};

Recording record(int frames, int points_per_frame) {
  Recording recording;
  const sim::World world = sim::featureHall();
  sim::LidarModel lidar;
  lidar.points_per_frame = points_per_frame;
  recording.truth = sim::weavingTrajectory({0, 0, 1.2}, 1.5, 1.0, 1.0, 15.0);
  sim::feedMotor(recording.motor, lidar, 0.0, frames * lidar.frame_duration);
  for (int k = 0; k < frames; ++k) {
    recording.scans.push_back(
        sim::simulateScan(world, recording.truth, lidar, k * lidar.frame_duration, k).scan);
  }
  return recording;
}

const Recording& shortRecording() {
  static const Recording recording = record(100, 20000);
  return recording;
}

// Arguments: scan voxel size in mm (300 is the default: docs/dev/architecture.md section 1), 1 for
// each frame's own velocity (the default), 0 for the filter's (OdometryConfig::frame_velocity_std_*),
// the registration budget (OdometryConfig::max_registration_points; 0: none) and the weakest
// direction's points it keeps (OdometryConfig::registration_weakest_points; 0: the budget alone).
void BM_RegisterScan20k(benchmark::State& state) {
  const Recording& recording = shortRecording();
  OdometryConfig config;
  config.initial_pose = recording.truth(0.0);
  config.scan_voxel_size = static_cast<double>(state.range(0)) / 1000.0;
  if (state.range(1) == 0) config.frame_velocity_std_linear = config.frame_velocity_std_angular = 0.0;
  config.max_registration_points = static_cast<int>(state.range(2));
  config.registration_weakest_points = static_cast<double>(state.range(3));
  auto odometry = std::make_unique<MotorizedLidarOdometry>(config);
  std::size_t next = 0, points = 0, used = 0, correspondences = 0, iterations = 0, associations = 0, frames = 0;
  for (auto _ : state) {
    if (next == recording.scans.size()) {
      state.PauseTiming();
      odometry = std::make_unique<MotorizedLidarOdometry>(config);
      next = 0;
      state.ResumeTiming();
    }
    const OdometryResult result = odometry->registerScan(recording.scans[next++], recording.motor);
    benchmark::DoNotOptimize(result.T_WB);
    points += result.points_in;
    used += result.points_used;
    correspondences += result.correspondences;
    iterations += static_cast<std::size_t>(result.iterations);
    associations += static_cast<std::size_t>(result.associations);
    ++frames;
  }
  state.counters["points_in"] = static_cast<double>(points) / frames;
  state.counters["points_used"] = static_cast<double>(used) / frames;
  state.counters["correspondences"] = static_cast<double>(correspondences) / frames;
  state.counters["iterations"] = static_cast<double>(iterations) / frames;
  state.counters["associations"] = static_cast<double>(associations) / frames;
  state.counters["map_voxels"] = static_cast<double>(odometry->localMap().size());
}
BENCHMARK(BM_RegisterScan20k)
    ->Args({300, 1, 0, 0})
    ->Args({500, 1, 0, 0})
    ->Args({300, 0, 0, 0})
    ->Args({300, 1, 4000, 0})
    ->Args({300, 1, 2000, 0})
    ->Args({300, 1, 2000, 100})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(5.0);

// A 65 s run (~97 m, the length of the synthetic hall) at 20k points per frame: the map stays
// bounded by map_radius.
void BM_LongRunMapSize(benchmark::State& state) {
  const int frames = 650;
  static const Recording recording = record(frames, 20000);
  for (auto _ : state) {
    OdometryConfig config;
    config.initial_pose = recording.truth(0.0);
    MotorizedLidarOdometry odometry(config);
    std::size_t max_map = 0, map_at_quarter = 0, max_bytes = 0;
    double worst_ms = 0.0, total_ms = 0.0, final_error = 0.0;
    for (int k = 0; k < frames; ++k) {
      const auto start = std::chrono::steady_clock::now();
      const OdometryResult result = odometry.registerScan(recording.scans[k], recording.motor);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      worst_ms = std::max(worst_ms, ms);
      total_ms += ms;
      max_map = std::max(max_map, odometry.localMap().size());
      max_bytes = std::max(max_bytes, odometry.localMap().memoryBytes());
      if (k == frames / 4) map_at_quarter = odometry.localMap().size();
      final_error = (result.T_WB.translation() - recording.truth(result.time).translation()).norm();
    }
    state.counters["map_voxels_max"] = static_cast<double>(max_map);
    state.counters["map_voxels_at_25pct"] = static_cast<double>(map_at_quarter);
    state.counters["map_voxels_final"] = static_cast<double>(odometry.localMap().size());
    state.counters["map_MB_max"] = static_cast<double>(max_bytes) / 1e6;
    state.counters["ms_per_frame_mean"] = total_ms / frames;
    state.counters["ms_per_frame_worst"] = worst_ms;
    state.counters["final_error_m"] = final_error;
    double distance = 0.0;
    for (int k = 1; k < frames; ++k) {
      distance +=
          (recording.truth(k * 0.1).translation() - recording.truth((k - 1) * 0.1).translation())
              .norm();
    }
    state.counters["distance_m"] = distance;
    state.counters["final_error_pct"] = 100.0 * final_error / distance;
  }
}
BENCHMARK(BM_LongRunMapSize)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uampc::lo

BENCHMARK_MAIN();
