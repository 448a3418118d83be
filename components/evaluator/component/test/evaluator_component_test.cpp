// The adapter in-process: estimates are paired with ground truth once ground truth covers them,
// and the run's files are written on shutdown into the output directory.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_info.hpp"
#include "uampc/run_files/time_series.hpp"
#include "uampc/runtime/testing/test_context.hpp"

// Bytes allocated through operator new while counting (the running-figures test below).
namespace {
std::atomic<bool> counting_allocations{false};
std::atomic<std::size_t> allocated_bytes{0};
}  // namespace

// Every form that malloc can serve is replaced, so that no block is allocated by one allocator and
// freed by another (std::stable_sort's buffer comes from the nothrow form: AddressSanitizer found
// it freed here after its own operator new). The aligned forms stay the library's, in pairs.
namespace {
void* countedAllocation(std::size_t size) noexcept {
  if (counting_allocations) allocated_bytes += size;
  return std::malloc(size ? size : 1);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = countedAllocation(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return countedAllocation(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return countedAllocation(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace uampc {
namespace {

geometry_msgs::msg::PoseStamped truthAt(double t) {
  geometry_msgs::msg::PoseStamped p;
  p.header().stamp(toMsg(Time::fromSeconds(t)));
  p.pose().position().x(t);
  p.pose().orientation().w(1.0);
  return p;
}

nav_msgs::msg::Odometry estimateAt(double t, double y_error) {
  nav_msgs::msg::Odometry o;
  o.header().stamp(toMsg(Time::fromSeconds(t)));
  o.pose().pose().position().x(t);
  o.pose().pose().position().y(y_error);
  o.pose().pose().orientation().w(1.0);
  return o;
}

std::size_t lineCount(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') ++lines;
  }
  return lines;
}

TEST(EvaluatorComponent, WritesTheRunFilesOnShutdownWithEveryCoveredEstimatePaired) {
  const std::filesystem::path out =
      std::filesystem::path(::testing::TempDir()) / ("evaluator_component_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  testing::TestOptions options;
  options.output_directory = out.string();
  {
    testing::TestContext ctx("evaluator", {}, options);
    for (int k = 0; k <= 10; ++k) {
      ctx.inject("ground_truth", truthAt(0.1 * k));
      ctx.inject("odometry", estimateAt(0.1 * k, 0.2));
    }
    ctx.inject("odometry", estimateAt(1.5, 0.2));  // after the last ground truth: never paired
    ctx.advanceTo(Time::fromSeconds(1.5));
    EXPECT_FALSE(std::filesystem::exists(out / "metrics.json"));  // written at the end only
    ctx.shutdown();
  }
  ASSERT_TRUE(std::filesystem::exists(out / "metrics.json"));
  EXPECT_EQ(lineCount(out / "estimate.tum"), 11u);
  EXPECT_EQ(lineCount(out / "ground_truth.tum"), 11u);
  std::ifstream estimate(out / "estimate.tum");
  std::string line;
  do {
    std::getline(estimate, line);
  } while (!line.empty() && line[0] == '#');
  double t = -1, x = -1, y = -1;
  std::istringstream(line) >> t >> x >> y;
  EXPECT_EQ(t, 0.0);
  EXPECT_DOUBLE_EQ(y, 0.2);
  std::filesystem::remove_all(out);
}

std::filesystem::path freshOutput(const std::string& name) {
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) /
                                    ("evaluator_component_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  return out;
}

// A run of the evaluator over nothing in `out`, to its metrics.json.
run_files::MetricsDocument runEmpty(const std::filesystem::path& out) {
  testing::TestOptions options;
  options.output_directory = out.string();
  {
    testing::TestContext ctx("evaluator", {}, options);
    ctx.advanceTo(Time::fromSeconds(0.5));
    ctx.shutdown();
  }
  const auto metrics = run_files::readMetricsFile((out / run_files::kMetricsFile).string());
  if (!metrics) throw std::runtime_error("no metrics.json in " + out.string());
  return *metrics;
}

// The running ATE published every report_period costs no memory in proportion to the run: with
// 20,000 pairs (2000 s at 10 Hz) one report allocates a few kilobytes, and publishes the RMSEs of
// the final metrics. It used to build the whole report, copying and sorting every pair (over 10 MB
// here), which the heap kept as it grew: most of the evaluator's growth in a long run
// (docs/results/soak.md).
TEST(EvaluatorComponent, RunningFiguresCostNoMemoryInProportionToTheRun) {
  const std::filesystem::path out = freshOutput("running");
  testing::TestOptions options;
  options.output_directory = out.string();
  {
    testing::TestContext ctx("evaluator", {}, options);
    constexpr int kPairs = 20000;
    for (int k = 0; k < kPairs; ++k) {
      ctx.inject("ground_truth", truthAt(0.1 * k));
      ctx.inject("odometry", estimateAt(0.1 * k, 0.01 * (k % 7)));
    }
    ctx.advanceTo(Time::fromSeconds(0.1 * kPairs - 1.0));
    const std::size_t reports = ctx.publishedCount("metrics");
    const double period = 5.0;  // report_period's default
    allocated_bytes = 0;
    counting_allocations = true;
    ctx.advanceBy(period);
    counting_allocations = false;
    ASSERT_EQ(ctx.publishedCount("metrics"), reports + 1);
    EXPECT_LT(allocated_bytes.load(), 64u * 1024u) << "bytes allocated by one running report of " << kPairs << " pairs";
    const msg::Metrics running = ctx.published<msg::Metrics>("metrics").back();
    ctx.shutdown();
    const auto metrics = run_files::readMetricsFile((out / run_files::kMetricsFile).string());
    ASSERT_TRUE(metrics);
    ASSERT_EQ(metrics->trajectory.paired, static_cast<std::uint64_t>(kPairs));
    for (const auto& v : running.values()) {
      if (v.name() == "ate") EXPECT_EQ(v.value(), metrics->trajectory.ate.unaligned_m.rmse);
      if (v.name() == "ate_aligned") EXPECT_EQ(v.value(), metrics->trajectory.ate.aligned_m.rmse);
    }
  }
  std::filesystem::remove_all(out);
}

TEST(EvaluatorComponent, MetricsSayWhatTheRunWasFromTheLaunchersRunInfo) {
  const std::filesystem::path out = freshOutput("run_info");
  run_files::RunInfo info;
  info.scene_copy = run_files::kSceneCopyFile;
  info.scene_source = "/somewhere/scene.yaml";
  info.seed = 42;
  info.uampc_version = "v1-2-gabc";
  info.fastdds_version = "2.9.1";
  info.components["evaluator"] = {{"type", "evaluator"}, {"params", {{"window", 5}}}};
  run_files::writeRunInfoFile((out / run_files::kRunInfoFile).string(), info);
  const run_files::MetricsDocument metrics = runEmpty(out);
  ASSERT_TRUE(metrics.run);
  EXPECT_EQ(metrics.run->seed, 42u);
  EXPECT_EQ(metrics.run->scene_source, "/somewhere/scene.yaml");
  EXPECT_EQ(metrics.run->uampc_version, "v1-2-gabc");
  EXPECT_EQ(metrics.run->components, info.components);
  std::filesystem::remove_all(out);
}

TEST(EvaluatorComponent, WithoutOrWithABrokenRunInfoTheMetricsAreStillWritten) {
  const std::filesystem::path out = freshOutput("no_run_info");
  EXPECT_FALSE(runEmpty(out).run);
  std::ofstream(out / run_files::kRunInfoFile) << "{\"scene\": \"scene.yaml\"}";  // lacks the rest
  EXPECT_FALSE(runEmpty(out).run);
  std::filesystem::remove_all(out);
}

uampc::msg::UncertaintyProfile profileAt(double t, std::size_t samples) {
  uampc::msg::UncertaintyProfile p;
  p.header().stamp(toMsg(Time::fromSeconds(t)));
  p.delta_theta(2 * M_PI / static_cast<double>(samples));
  p.command(3.6);
  p.samples(std::vector<double>(samples, 0.25));
  return p;
}

TEST(EvaluatorComponent, UncertaintyStaysRectangularWhenTheSampleCountChanges) {
  const std::filesystem::path out = freshOutput("uncertainty");
  testing::TestOptions options;
  options.output_directory = out.string();
  {
    testing::TestContext ctx("evaluator", {}, options);
    ctx.inject("profile", profileAt(0.1, 72));
    ctx.inject("profile", profileAt(0.2, 36));  // cannot fit the columns: left out, said once
    ctx.inject("profile", profileAt(0.3, 72));
    ctx.advanceTo(Time::fromSeconds(0.5));
    ctx.shutdown();
  }
  const auto rows = run_files::readUncertainty((out / run_files::kUncertaintyFile).string());  // checks the shape
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].time, 0.1);
  EXPECT_EQ(rows[1].time, 0.3);
  EXPECT_EQ(rows[1].samples.size(), 72u);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace uampc
