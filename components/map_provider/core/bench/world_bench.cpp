// How long worlds take to build, sample and trajectories to interpolate.
#include <benchmark/benchmark.h>

#include "uampc/world/generated_paths.hpp"
#include "uampc/world/point_sampling.hpp"
#include "uampc/world/procedural_worlds.hpp"

namespace uampc::world {
namespace {

void BM_MakeCampus(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(makeCampus(CampusConfig{}, 1));
  state.counters["triangles"] = static_cast<double>(makeCampus(CampusConfig{}, 1).size());
}
BENCHMARK(BM_MakeCampus)->Unit(benchmark::kMillisecond);

void BM_SampleCampus(benchmark::State& state) {
  const TriangleMesh mesh = makeCampus(CampusConfig{}, 1);
  std::size_t n = 0;
  for (auto _ : state) n = sampleSurface(mesh, 10.0, 1).size();
  state.counters["points"] = static_cast<double>(n);
}
BENCHMARK(BM_SampleCampus)->Unit(benchmark::kMillisecond);

void BM_PoseAt(benchmark::State& state) {
  GeneratedPathConfig config;
  config.closed = true;
  const Trajectory t = pathThroughWaypoints(campusLoopWaypoints(CampusConfig{}, 1.0), config);
  double time = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(t.poseAt(time));
    time += 1e-5;
    if (time > t.endTime()) time = 0.0;
  }
}
BENCHMARK(BM_PoseAt);

}  // namespace
}  // namespace uampc::world

BENCHMARK_MAIN();
