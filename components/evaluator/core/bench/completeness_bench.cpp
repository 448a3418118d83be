// CMPLT insertion rate for 20k-point scans (a Mid-360-like frame at 200k points/s, 10 Hz); each
// 5 s window holds 50 scans. Two clouds: points uniform in an 80 x 80 x 12 m box (worst case:
// almost every point a new voxel, the total set grows to ~600k voxels) and points on surfaces
// (ground within 30 m and a fixed round wall) around a sensor moving at 1 m/s, closer to real
// scans.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "uampc/evaluator/completeness.hpp"

namespace uampc::evaluator {
namespace {

std::vector<std::vector<Eigen::Vector3f>> makeScans(int scans, int points_per_scan) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> uniform(-40.0f, 40.0f);
  std::uniform_real_distribution<float> height(-2.0f, 10.0f);
  std::vector<std::vector<Eigen::Vector3f>> result(static_cast<std::size_t>(scans));
  for (auto& scan : result) {
    scan.reserve(static_cast<std::size_t>(points_per_scan));
    for (int i = 0; i < points_per_scan; ++i)
      scan.emplace_back(uniform(rng), uniform(rng), height(rng));
  }
  return result;
}

std::vector<std::vector<Eigen::Vector3f>> makeSurfaceScans(int scans, int points_per_scan) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<std::vector<Eigen::Vector3f>> result(static_cast<std::size_t>(scans));
  for (std::size_t k = 0; k < result.size(); ++k) {
    const Eigen::Vector3f sensor(0.1f * static_cast<float>(k), 0.0f, 0.0f);
    auto& scan = result[k];
    for (int i = 0; i < points_per_scan; ++i) {
      const float a = 6.2831853f * unit(rng);
      if (i % 2 == 0) {  // ground, out to 30 m
        const float r = 30.0f * std::sqrt(unit(rng));
        scan.push_back(sensor + Eigen::Vector3f(r * std::cos(a), r * std::sin(a), -1.5f));
      } else {  // a fixed round wall of radius 30 m, 10 m high
        scan.push_back(
            Eigen::Vector3f(30.0f * std::cos(a), 30.0f * std::sin(a), -1.5f + 10.0f * unit(rng)));
      }
    }
  }
  return result;
}

void run(benchmark::State& state, const std::vector<std::vector<Eigen::Vector3f>>& scans) {
  Completeness cmplt;
  double stamp = 0.0;
  std::size_t k = 0;
  for (auto _ : state) {
    cmplt.addScan(stamp, scans[k % scans.size()]);
    stamp += 0.1;
    ++k;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
  state.counters["total_voxels"] = static_cast<double>(cmplt.totalVoxels());
}
void BM_CompletenessUniformBox(benchmark::State& state) {
  run(state, makeScans(100, static_cast<int>(state.range(0))));
}
void BM_CompletenessSurfaces(benchmark::State& state) {
  run(state, makeSurfaceScans(500, static_cast<int>(state.range(0))));
}
BENCHMARK(BM_CompletenessUniformBox)->Arg(20000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompletenessSurfaces)->Arg(20000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace uampc::evaluator

BENCHMARK_MAIN();
