// CMPLT insertion rate: 20k-point scans (a Mid-360-like frame at 200k points/s, 10 Hz) spread over
// a 40 m box, as the evaluator sees them; each 5 s window holds 50 scans.
#include <benchmark/benchmark.h>

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
    for (int i = 0; i < points_per_scan; ++i) scan.emplace_back(uniform(rng), uniform(rng), height(rng));
  }
  return result;
}

void BM_CompletenessAddScan(benchmark::State& state) {
  const auto scans = makeScans(100, static_cast<int>(state.range(0)));
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
BENCHMARK(BM_CompletenessAddScan)->Arg(20000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace uampc::evaluator

BENCHMARK_MAIN();
