// How long a calibration takes from 30 s of a still Mid-360 in the campus (docs/dev/testing.md:
// benchmarks measure, tests assert). The target: under a minute on one core.
#include <benchmark/benchmark.h>

#include "../test/simulated_recording.hpp"
#include "uampc/calibration/rig_estimator.hpp"

namespace uampc::calibration {
namespace {

void BM_Calibrate30sOfMid360(benchmark::State& state) {
  test::SimulatedRig rig;
  rig.world = "campus";
  rig.seconds = 30.0;
  frames::MountingError error;
  error.rotation_rpy = {0.01, -0.01, 0.0};
  error.offset = {0.01, 0.01, 0.0};
  error.time_offset = 0.005;
  rig.truth = frames::withMountingError(frames::MotorLidarCalibration::referenceRig(), error);
  const RigRecording recording = test::simulatedRecording(rig);
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimateRig(recording, frames::MotorLidarCalibration::referenceRig()));
  }
}
BENCHMARK(BM_Calibrate30sOfMid360)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uampc::calibration

BENCHMARK_MAIN();
