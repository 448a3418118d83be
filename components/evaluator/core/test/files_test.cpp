// Tests of the files the evaluator writes: TUM trajectories, metrics JSON, CSV series (their format:
// libs/run_files).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "test_directory.hpp"
#include "uampc/evaluator/pose_interpolator.hpp"
#include "uampc/evaluator/report_files.hpp"
#include "uampc/evaluator/tum_trajectory.hpp"

namespace uampc::evaluator {
namespace {

std::string contentOf(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Runs a Python check on a JSON file: the file must parse with json.load, then the script (with
// the parsed object as d) must not raise.
int checkJsonWithPython(const std::string& path, const std::string& script) {
  const std::string command = "python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); " + script + "' " + path;
  return std::system(command.c_str());
}

template <typename Exception, typename Function>
void expectThrowNaming(Function function, const std::string& text) {
  try {
    function();
    ADD_FAILURE() << "no exception";
  } catch (const Exception& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(TumTrajectory, RoundTripsAtFullPrecision) {
  test::TestDirectory directory;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-1000.0, 1000.0);
  std::vector<TimedPose> poses;
  for (int k = 0; k < 100; ++k) {
    TimedPose p;
    p.time = 1700000000.0 + 0.1 * k + 1e-7;  // unix-like stamps need all 17 digits
    p.pose.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    p.pose.translation() = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)) / 3.0;
    poses.push_back(p);
  }
  const std::string path = directory.file("trajectory.tum");
  writeTumTrajectory(path, poses);
  const std::vector<TimedPose> read = readTumTrajectory(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].time, poses[i].time);  // bit-exact
    EXPECT_EQ(read[i].pose.translation(), poses[i].pose.translation());
    EXPECT_LT((read[i].pose.linear() - poses[i].pose.linear()).norm(), 1e-14);
  }
  // The format itself: 8 fields, quaternion last with qw >= 0.
  std::istringstream lines(contentOf(path));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line[0], '#');
  std::getline(lines, line);
  std::istringstream fields(line);
  double v[8];
  for (double& x : v) ASSERT_TRUE(fields >> x);
  EXPECT_NEAR(Eigen::Vector4d(v[4], v[5], v[6], v[7]).norm(), 1.0, 1e-15);
  EXPECT_GE(v[7], 0.0);
}

TEST(TumTrajectory, ErrorsNameThePathAndLine) {
  test::TestDirectory directory;
  const std::string path = directory.file("bad.tum");
  std::ofstream(path) << "# comment\n\n0 1 2 3 0 0 0 1\n1 2 3 x 0 0 0 1\n";
  expectThrowNaming<std::runtime_error>([&] { readTumTrajectory(path); }, path + ":4");
  std::ofstream(path) << "0 1 2 3 0 0 0\n";
  expectThrowNaming<std::runtime_error>([&] { readTumTrajectory(path); }, path + ":1");
  expectThrowNaming<std::runtime_error>([&] { readTumTrajectory(directory.file("missing.tum")); },
                                        directory.file("missing.tum"));
  expectThrowNaming<std::runtime_error>([&] { writeTumTrajectory("/nonexistent/t.tum", {}); }, "/nonexistent/t.tum");
}

TEST(MetricsFile, ReportsBecomeValidJson) {
  test::TestDirectory directory;
  const PoseInterpolator truth(
      {{0.0, Eigen::Isometry3d::Identity()}, {100.0, Eigen::Isometry3d(Eigen::Translation3d(200, 0, 0))}});
  TrajectoryEvaluator evaluator([&truth](double t) { return truth(t); });
  for (int k = 0; k <= 1000; ++k) {
    evaluator.addEstimate(0.1 * k, Eigen::Isometry3d(Eigen::Translation3d(2.0 * k * 0.1 * 1.01, 0, 0)));
  }
  Completeness cmplt;
  cmplt.addScan(0.0, {{0, 0, 0}});
  run_files::MetricsDocument metrics;
  metrics.sim_time = 100.0;
  metrics.trajectory = toSummary(evaluator.report());
  metrics.cmplt = toSummary(cmplt.report());
  const std::string path = directory.file("metrics.json");
  run_files::writeMetricsFile(path, metrics);
  EXPECT_EQ(checkJsonWithPython(path,
                                "t = d[\"trajectory\"]; assert t[\"paired\"] == 1001; "
                                "assert abs(t[\"distance_m\"] - 200) < 1e-9; "
                                "assert abs(t[\"rpe_10m\"][\"translation_percent\"][\"mean\"] - 1) < 1e-6; "
                                "assert t[\"rpe_100m\"][\"segment_length_m\"] == 100; "
                                "assert t[\"ate\"][\"aligned_m\"][\"rmse\"] >= 0; "
                                "assert d[\"cmplt\"][\"cmplt\"] is None; assert d[\"sim_time\"] == 100"),
            0)
      << contentOf(path);
}

TEST(RunFiles, SeriesFiles) {
  test::TestDirectory directory;
  writeAteSeriesCsv(directory.file("ate.csv"), {{1.0, 0.5, 0.25}});
  EXPECT_EQ(contentOf(directory.file("ate.csv")), "time,ate_m,ate_aligned_m\n1,0.5,0.25\n");
  CompletenessWindow window;
  window.index = 2;
  window.start = 10.0;
  window.end = 15.0;
  window.voxels = 7;
  window.scans = 50;
  window.points = 1000;
  window.complete = true;
  writeCompletenessWindowsCsv(directory.file("cmplt.csv"), {window});
  EXPECT_EQ(contentOf(directory.file("cmplt.csv")),
            "window,start,end,voxels,scans,points,complete\n2,10,15,7,50,1000,1\n");
}

}  // namespace
}  // namespace uampc::evaluator
