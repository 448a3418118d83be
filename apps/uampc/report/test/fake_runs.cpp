#include "report/test/fake_runs.hpp"

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "experiment/backends/experiment_runner.hpp"
#include "uampc/evaluator/depth_colouring.hpp"
#include "uampc/evaluator/voxel_octree.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/time_series.hpp"

namespace fs = std::filesystem;

namespace uampc::test {

namespace {

struct FakeFigures {
  double ate;
  double cmplt;               // NaN: written as null
  double runaway_time = NAN;  // s, when the run lost track; NaN: it never did
};

// [scene][controller][seed]
const std::map<std::tuple<std::string, std::string, int>, FakeFigures> kFigures{
    {{"alpha", "ua_mpc", 1}, {1.0, 100}},       {{"alpha", "ua_mpc", 2}, {2.0, 110}},
    {{"alpha", "constant_3.6", 1}, {4.0, 100}}, {{"alpha", "constant_3.6", 2}, {6.0, 100}},
    {{"alpha", "zero", 1}, {8.0, NAN, 3.5}},    {{"alpha", "zero", 2}, {9.0, NAN, 14.25}},
    {{"beta", "ua_mpc", 1}, {3.0, 50}},         {{"beta", "ua_mpc", 2}, {4.0, 50}},
    {{"beta", "constant_3.6", 1}, {10.0, 40}},  {{"beta", "constant_3.6", 2}, {20.0, 60, 7.0}},
    {{"beta", "zero", 1}, {29.5, 20}},
};

// The ground truth's path length (trajectory.distance_m), the same for every run of a scene.
constexpr double kAlphaDistance = 50.0, kBetaDistance = 200.0;
constexpr double kSimTimeS = 10.0;  // every fake run's, its scene's whole length
const app::SceneEnd kSceneEnd{kSimTimeS, 0.005};

// metrics.json as the evaluator writes it, with the figures the report reads.
run_files::MetricsDocument fakeMetrics(const FakeFigures& f, double distance) {
  run_files::MetricsDocument m;
  m.sim_time = kSimTimeS;
  m.trajectory.distance_m = distance;
  m.trajectory.ate.unaligned_m.rmse = f.ate;
  m.trajectory.ate.aligned_m.rmse = f.ate / 2;
  run_files::RpeSummary rpe10, rpe100;  // no 100 m segment: its figures stay NaN (null)
  rpe10.segment_length_m = 10;
  rpe10.translation_m.rmse = 0.5;
  rpe100.segment_length_m = 100;
  m.trajectory.rpe = {rpe10, rpe100};
  m.trajectory.speed_error.max_m_s = 0.5;
  if (std::isfinite(f.runaway_time)) m.trajectory.speed_error.first_runaway_time = f.runaway_time;
  m.cmplt.cmplt = f.cmplt;
  m.cmplt_ground_truth.cmplt = f.cmplt * 1.1;
  m.motor.mean_speed = 3.6;
  return m;
}

void writeRun(const fs::path& dir, const FakeFigures& f, double distance, bool ua_mpc) {
  using run_files::inDirectory;
  const std::string run = dir.string();
  fs::create_directories(dir);
  run_files::writeMetricsFile(inDirectory(run, run_files::kMetricsFile), fakeMetrics(f, distance));
  std::vector<run_files::AteRow> ate;
  std::vector<run_files::MotorRow> motor;
  std::string estimate, truth;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * 0.1;
    const double e = f.ate * t / 10.0;
    ate.push_back({t, e, e / 2});
    truth += std::to_string(t) + " " + std::to_string(t) + " " + std::to_string(std::sin(t)) + " 1 0 0 0 1\n";
    estimate += std::to_string(t) + " " + std::to_string(t + e / 10) + " " + std::to_string(std::sin(t) + e / 10) +
                " 1 0 0 0 1\n";
  }
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * 0.005;
    motor.push_back({t, 3.6 * t, 3.6 + std::sin(t), 3.6});
  }
  run_files::writeRows(inDirectory(run, run_files::kAteFile), ate);
  run_files::writeRows(inDirectory(run, run_files::kMotorFile), motor);
  writeText(inDirectory(run, run_files::kEstimateFile), estimate);
  writeText(inDirectory(run, run_files::kGroundTruthFile), truth);
  if (ua_mpc) {
    run_files::UncertaintyWriter u(inDirectory(run, run_files::kUncertaintyFile));
    for (int i = 0; i < 100; ++i) {
      run_files::UncertaintyRow row{i * 0.1, 0.0, 2 * M_PI / 72, 3.6, {}};
      for (int k = 0; k < 72; ++k) row.samples.push_back(0.1 + 0.05 * std::sin(k * 0.2 + i * 0.1));
      u.add(row);
    }
    // Six panorama snapshots, as the evaluator names them; the report shows four.
    const std::string panoramas = inDirectory(run, run_files::kPanoramaDirectory);
    fs::create_directories(panoramas);
    for (int k = 0; k < 6; ++k) {
      std::vector<float> depth(36 * 18);
      for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = static_cast<float>((i + 7 * k) % 45);
      evaluator::writePng(inDirectory(panoramas, run_files::panoramaSnapshotName(1.5 * k)),
                          evaluator::colourDepth(depth, 36, 18, 40.0));
    }
  }
  std::vector<Eigen::Vector3i> voxels;
  for (int x = -4; x < 24; ++x) {
    for (int y = -6; y < 6; ++y) voxels.emplace_back(x, y, (x * y) % 3 == 0 ? 1 : 0);
  }
  evaluator::writeVoxelOctree(inDirectory(run, run_files::kScannedVoxelsFile), voxels, 0.5);
  writeText(inDirectory(run, run_files::kRunLog), "uampc: 10 s of sim time in 4 s (2.5x real time)\n");
}

}  // namespace

void writeText(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

FakeExperiment makeFakeExperiment(const std::string& directory) {
  FakeExperiment fake;
  fake.directory = directory + "/out";
  writeText(directory + "/scenes/alpha.yaml", "components: {}\n");
  writeText(directory + "/scenes/beta.yaml", "components: {}\n");
  writeText(directory + "/fake.yaml",
            "name: fake\nseeds: [1, 2]\nscenes:\n  - {name: alpha, scene: scenes/alpha.yaml}\n"
            "  - {name: beta, scene: scenes/beta.yaml}\ncontrollers:\n"
            "  - {name: ua_mpc, overrides: [controller.mode=ua_mpc]}\n"
            "  - {name: constant_3.6, overrides: [controller.mode=constant]}\n"
            "  - {name: zero, overrides: [controller.mode=zero]}\n");
  fake.experiment = app::loadExperiment(directory + "/fake.yaml", {});
  for (const auto& run : app::planRuns(fake.experiment, {})) {
    app::RunResult r;
    r.scene = fake.experiment.scenes[run.scene].name;
    r.controller = fake.experiment.controllers[run.controller].name;
    r.seed = run.seed;
    r.directory = run.directory;
    const fs::path dir = fs::path(fake.directory) / run.directory;
    const auto figures = kFigures.find({r.scene, r.controller, static_cast<int>(r.seed)});
    if (figures != kFigures.end()) {
      writeRun(dir, figures->second, r.scene == "alpha" ? kAlphaDistance : kBetaDistance, r.controller == "ua_mpc");
      run_files::writeDoneMarker(dir.string(), 4.5);
    } else {
      writeText(run_files::inDirectory(dir.string(), run_files::kRunLog), "something broke\n");
    }
    if (app::isRunComplete(dir.string(), kSceneEnd)) {
      r.status = app::RunStatus::kReused;
      r.exit_code = 0;
      app::readRunOutputs(dir.string(), r);
    } else {
      r.status = app::RunStatus::kFailed;
      r.failure = "exit code 1";
    }
    fake.results.push_back(r);
  }
  return fake;
}

}  // namespace uampc::test
