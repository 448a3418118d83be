// Replaying recorded control steps: the run's own options give back the run's commands, and the
// options change what they should.
#include "control_replay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "uampc/mpc/uncertainty_surrogate.hpp"

namespace uampc::tools {
namespace {

constexpr int kSamples = 72;
constexpr double kStep = 2.0 * M_PI / kSamples;

// U over one turn seen from theta: two good directions, with a per-step disturbance that a filter
// over steps should smooth (the scene does not change, the estimate of it does).
std::vector<double> samplesAt(double theta, int step) {
  std::vector<double> u(kSamples);
  for (int s = 0; s < kSamples; ++s) {
    const double angle = theta + s * kStep;
    u[s] = 1.0 + 0.8 * std::cos(2.0 * angle) + 0.3 * std::sin(12.9898 * (step * 78.233 + s));
  }
  return u;
}

// A closed-loop run of the default controller, written as the evaluator writes uncertainty.csv.
std::string writeRun(int steps) {
  const std::string path = ::testing::TempDir() + "/uncertainty.csv";
  std::ofstream out(path);
  out << "time,theta_start,delta_theta,command,samples...\n";
  out.precision(17);
  const mpc::MotorMpc mpc;
  double theta = 0.0;
  for (int k = 0; k < steps; ++k) {
    const std::vector<double> u = samplesAt(theta, k);
    const double command = mpc.solve(mpc::UncertaintySurrogate(theta, kStep, u), theta).speeds.front();
    out << 0.1 * k << "," << theta << "," << kStep << "," << command;
    for (double v : u) out << "," << v;
    out << "\n";
    theta += command * 0.1;
  }
  return path;
}

TEST(ControlReplay, TheRunsOwnOptionsGiveBackItsCommands) {
  const std::vector<ControlRecord> records = readControlRecords(writeRun(60));
  ASSERT_EQ(records.size(), 60u);
  const ReplayStats stats = replayControl(records, ReplayOptions{});
  EXPECT_LT(stats.max_difference, 1e-9);
  EXPECT_NEAR(stats.replayed_change_rms, stats.recorded_change_rms, 1e-9);
  EXPECT_GT(stats.recorded_change_rms, 0.0);
}

TEST(ControlReplay, FilteringTheSamplesOverStepsCalmsTheCommand) {
  const std::vector<ControlRecord> records = readControlRecords(writeRun(200));
  ReplayOptions filtered;
  filtered.filter_weight = 0.2;
  EXPECT_LT(replayControl(records, filtered).replayed_change_rms,
            replayControl(records, ReplayOptions{}).replayed_change_rms);
  filtered.filter_weight = 0.0;
  EXPECT_THROW(replayControl(records, filtered), std::invalid_argument);
}

TEST(ControlReplay, ACoarserSampleStepUsesEveryKthSample) {
  const std::vector<ControlRecord> records = readControlRecords(writeRun(40));
  ReplayOptions coarse;
  coarse.sample_stride = 2;  // 10-degree samples
  const ReplayStats stats = replayControl(records, coarse);
  // The same as solving on every other sample by hand.
  const mpc::MotorMpc mpc;
  std::vector<double> half;
  for (int s = 0; s < kSamples; s += 2) half.push_back(records[7].samples[s]);
  const double expected =
      mpc.solve(mpc::UncertaintySurrogate(records[7].theta_start, 2 * kStep, half), records[7].theta_start)
          .speeds.front();
  EXPECT_DOUBLE_EQ(stats.commands[7], expected);
  coarse.sample_stride = 5;  // does not divide 72
  EXPECT_THROW(replayControl(records, coarse), std::invalid_argument);
}

TEST(ControlReplay, MalformedRowsNameTheirLine) {
  const std::string path = ::testing::TempDir() + "/broken_uncertainty.csv";
  {
    std::ofstream out(path);
    out << "time,theta_start,delta_theta,command,samples...\n0.1,0,0.5,3.6,1,2\n";
  }
  try {
    readControlRecords(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(path);
    out << "header\n0.1,0,x,3.6,1,2,3\n";
  }
  EXPECT_THROW(readControlRecords(path), std::runtime_error);
  EXPECT_THROW(readControlRecords(path + ".missing"), std::runtime_error);
}

}  // namespace
}  // namespace uampc::tools
