// Rays per second and milliseconds per frame on the campus world, on one core.
// Target: a 10 Hz Mid-360 frame (20k rays) in at most 10 ms, i.e. 2 million rays/s.
#include <benchmark/benchmark.h>

#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/generated_paths.hpp"
#include "uampc/world/procedural_worlds.hpp"

namespace uampc::raycaster {
namespace {

const world::TriangleMesh& campus() {
  static const world::TriangleMesh mesh = world::makeCampus(world::CampusConfig{}, 1);
  return mesh;
}

const world::Trajectory& campusLoop() {
  static const world::Trajectory t = [] {
    world::GeneratedPathConfig config;
    config.closed = true;
    return world::pathThroughWaypoints(world::campusLoopWaypoints(world::CampusConfig{}, 1.0),
                                       config);
  }();
  return t;
}

// Frames along the campus loop, the motor at 3.6 rad/s; time per frame and rays per second.
void castFrames(benchmark::State& state, const lidar::LidarModel& model, bool packets, bool noisy = false,
                FrameTiming timing = FrameTiming::kContinuous) {
  RayCasterConfig config;
  config.model = model;
  config.use_packets = packets;
  config.frame_timing = timing;
  if (noisy) {  // the model's datasheet precision, as the paper scenes set it
    config.range_noise_stddev = model.range_precision;
    config.angular_noise_stddev = model.angular_precision_deg * M_PI / 180.0;
  }
  RayCaster caster(campus(), config);
  const world::Trajectory& trajectory = campusLoop();
  auto pose = [&](double t) { return trajectory.poseAt(t); };
  auto theta = [](double t) { return 3.6 * t; };
  std::uint64_t frame = 0;
  std::size_t rays = 0, returns = 0;
  const auto frames_in_loop = static_cast<std::uint64_t>(trajectory.duration() * 10.0) - 2;
  for (auto _ : state) {
    const Scan scan = caster.castFrame(frame, 0.1 * static_cast<double>(frame), pose, theta);
    rays += scan.rays;
    returns += scan.points.size();
    frame = (frame + 1) % frames_in_loop;
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["returns_per_frame"] =
      static_cast<double>(returns) / static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(caster.scene().triangleCount());
}

void BM_Mid360FramePackets(benchmark::State& s) { castFrames(s, lidar::livoxMid360(), true); }
void BM_Mid360FrameSingleRays(benchmark::State& s) { castFrames(s, lidar::livoxMid360(), false); }
// With range and angular noise: three normal draws per ray (Box-Muller, a log and a cosine each).
void BM_Mid360FrameNoisy(benchmark::State& s) { castFrames(s, lidar::livoxMid360(), true, true); }
// Snapshot frames (the reference simulator's): one pose per frame instead of knots over it.
void BM_Mid360FrameSnapshot(benchmark::State& s) {
  castFrames(s, lidar::livoxMid360(), true, false, FrameTiming::kSnapshot);
}
void BM_Vlp16Frame(benchmark::State& s) { castFrames(s, lidar::velodyneVlp16(), true); }
void BM_AviaFrame(benchmark::State& s) { castFrames(s, lidar::livoxAvia(), true); }
BENCHMARK(BM_Mid360FramePackets)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Mid360FrameSingleRays)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Mid360FrameNoisy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Mid360FrameSnapshot)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vlp16Frame)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AviaFrame)->Unit(benchmark::kMillisecond);

// The parts of a frame: the pattern, and the bare ray casting.
void BM_Mid360Pattern(benchmark::State& state) {
  const ScanPatternGenerator generator(lidar::livoxMid360());  // as the raycaster keeps it
  std::vector<PatternPoint> pattern;
  std::uint64_t frame = 0;
  for (auto _ : state) {
    generator.generate(frame++, pattern);
    benchmark::DoNotOptimize(pattern.data());
  }
}
BENCHMARK(BM_Mid360Pattern)->Unit(benchmark::kMillisecond);

void BM_SceneIntersectOnly(benchmark::State& state) {
  RayCastScene scene(campus());
  const auto pattern = scanPattern(lidar::livoxMid360(), 0);
  std::vector<Ray> rays;
  for (const auto& p : pattern) rays.push_back({Eigen::Vector3f(-37, 0, 1.5), p.direction, 40.0f});
  std::vector<Hit> hits;
  // 0: single rays; 1: packets in firing order; 2: packets grouped by laser (as RayCaster casts)
  const bool packets = state.range(0) != 0;
  const std::vector<std::uint32_t> order = state.range(0) == 2 ? packetOrder(pattern) : std::vector<std::uint32_t>{};
  for (auto _ : state) {
    if (packets) {
      scene.intersect(rays, hits, order);
    } else {
      for (const auto& r : rays) benchmark::DoNotOptimize(scene.intersect(r));
    }
  }
  state.counters["rays_per_s"] = benchmark::Counter(
      static_cast<double>(rays.size() * state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SceneIntersectOnly)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_BuildCampusScene(benchmark::State& state) {
  for (auto _ : state) RayCastScene scene(campus());
}
BENCHMARK(BM_BuildCampusScene)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace uampc::raycaster

BENCHMARK_MAIN();
