// Milliseconds per UA-MPC control step with a 100k-point local map on one core.
// Target: at most 5 ms for depth map + normals + 72 U samples + solve.
#include <benchmark/benchmark.h>

#include <random>

#include "../test/synthetic_scenes.hpp"
#include "uampc/simd/dispatch.hpp"
#include "uampc/mpc/ua_mpc_controller.hpp"
#include "uampc/mpc/uncertainty_surrogate.hpp"

namespace {

using uampc::mpc::test::Cloud;

// A 24 x 12 x 4 m hall with two rows of pillars and scattered boxes, 100k points with a little
// noise, like an LO local map of the last seconds (points spread over surfaces, not a grid).
Cloud hall(std::size_t count) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  struct Quad {
    Eigen::Vector3d origin, e1, e2;
  };
  std::vector<Quad> quads = {
      {{-12, -6, 0}, {24, 0, 0}, {0, 12, 0}},  // floor
      {{-12, -6, 4}, {24, 0, 0}, {0, 12, 0}},  // ceiling
      {{-12, -6, 0}, {24, 0, 0}, {0, 0, 4}},   {{-12, 6, 0}, {24, 0, 0}, {0, 0, 4}},
      {{-12, -6, 0}, {0, 12, 0}, {0, 0, 4}},   {{12, -6, 0}, {0, 12, 0}, {0, 0, 4}}};
  for (int i = -2; i <= 2; ++i) {
    for (double y : {-3.0, 3.0}) {
      const Eigen::Vector3d c(4.0 * i, y, 0.0);
      quads.push_back({c + Eigen::Vector3d(-0.3, -0.3, 0), {0.6, 0, 0}, {0, 0, 4}});
      quads.push_back({c + Eigen::Vector3d(-0.3, 0.3, 0), {0.6, 0, 0}, {0, 0, 4}});
      quads.push_back({c + Eigen::Vector3d(-0.3, -0.3, 0), {0, 0.6, 0}, {0, 0, 4}});
      quads.push_back({c + Eigen::Vector3d(0.3, -0.3, 0), {0, 0.6, 0}, {0, 0, 4}});
    }
  }
  std::vector<double> area;
  double total = 0.0;
  for (const Quad& q : quads) total += q.e1.cross(q.e2).norm(), area.push_back(total);
  Cloud cloud;
  cloud.reserve(count);
  while (cloud.size() < count) {
    const double pick = u01(rng) * total;
    const Quad& q = quads[std::lower_bound(area.begin(), area.end(), pick) - area.begin()];
    cloud.push_back(q.origin + u01(rng) * q.e1 + u01(rng) * q.e2 +
                    Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  return cloud;
}

Eigen::Isometry3d basePose() {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.translation() = Eigen::Vector3d(1.3, 0.4, 1.2);
  T_WB.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T_WB;
}

// The local map as the mpc component holds it: float32, as the LO publishes it.
std::vector<Eigen::Vector3f> asFloat(const Cloud& cloud) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(cloud.size());
  for (const auto& p : cloud) out.push_back(p.cast<float>());
  return out;
}

// Args: local-map points, panorama degrees per pixel (1 is what the mpc component ships, see
// PanoramicDepthMap::Config; 2 is the cheaper setting it replaced), and U's ray grid in degrees
// (5 is the default, UncertaintyModel::Config; 10 is a quarter of the rays, which rank the motor
// angles worse: docs/results/u-check.md).
void BM_ControlStep(benchmark::State& state) {
  const std::vector<Eigen::Vector3f> cloud = asFloat(hall(static_cast<std::size_t>(state.range(0))));
  uampc::mpc::UaMpcController::Config config;
  config.depth_map.width = static_cast<int>(360 / state.range(1));
  config.depth_map.height = static_cast<int>(180 / state.range(1));
  config.uncertainty.azimuth_step = config.uncertainty.elevation_step = static_cast<double>(state.range(2)) * M_PI / 180.0;
  uampc::mpc::UaMpcController controller(config);
  double theta = 0.0;
  uampc::mpc::UaMpcController::Decision decision;
  for (auto _ : state) {
    decision = controller.stepFloat(basePose(), cloud, theta);
    benchmark::DoNotOptimize(decision.omega);
    theta += 0.36;
  }
  state.counters["depth_map_ms"] = decision.timings.depth_map_ms;
  state.counters["uncertainty_ms"] = decision.timings.uncertainty_ms;
  state.counters["solve_ms"] = decision.timings.solve_ms;
  state.counters["solver_iterations"] = decision.plan.iterations;
  state.counters["occupied_px"] = static_cast<double>(controller.depthMap().occupiedCount());
}
BENCHMARK(BM_ControlStep)
    ->Args({100000, 2, 5})
    ->Args({100000, 1, 5})
    ->Args({100000, 1, 10})
    ->Unit(benchmark::kMillisecond);

void BM_DepthMap(benchmark::State& state) {
  const std::vector<Eigen::Vector3f> cloud = asFloat(hall(100000));
  uampc::mpc::PanoramicDepthMap map;
  for (auto _ : state) {
    map.renderFloat(cloud, basePose());
    benchmark::DoNotOptimize(map.occupiedCount());
  }
}
BENCHMARK(BM_DepthMap)->Unit(benchmark::kMillisecond);

void BM_UncertaintySamples(benchmark::State& state) {
  const Cloud cloud = hall(100000);
  uampc::mpc::PanoramicDepthMap map;
  map.render(cloud, basePose());
  uampc::mpc::DepthMapNormals normals;
  const uampc::mpc::UncertaintyModel model;
  int computed = 0;
  for (auto _ : state) {
    normals.reset(map);  // normals are recomputed on demand, as in a control step
    const auto samples = model.sample(map, normals, 0.3, 2.0 * M_PI / 72, 72);
    benchmark::DoNotOptimize(samples.data());
    computed = normals.computedCount();
  }
  state.counters["normals_computed"] = computed;
}
BENCHMARK(BM_UncertaintySamples)->Unit(benchmark::kMillisecond);

void BM_Solve(benchmark::State& state) {
  const Cloud cloud = hall(100000);
  uampc::mpc::PanoramicDepthMap map;
  map.render(cloud, basePose());
  uampc::mpc::DepthMapNormals normals;
  normals.reset(map);
  const uampc::mpc::UncertaintyModel model;
  const double step = uampc::mpc::UncertaintySurrogate::turnStep(72);
  const uampc::mpc::UncertaintySurrogate surrogate(0.3, step,
                                                   model.sample(map, normals, 0.3, step, 72));
  const uampc::mpc::MotorMpc mpc;
  for (auto _ : state) {
    const auto plan = mpc.solve(surrogate, 0.3);
    benchmark::DoNotOptimize(plan.speeds.data());
  }
}
BENCHMARK(BM_Solve)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  // Which build of the panorama's loops ran (UAMPC_SIMD=baseline forces the SSE2 one).
  benchmark::AddCustomContext("uampc_simd", uampc::simd::instructionSetName());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
