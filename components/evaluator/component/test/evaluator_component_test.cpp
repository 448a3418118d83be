// The adapter in-process: estimates are paired with ground truth once ground truth covers them,
// and the run's files are written on shutdown into the output directory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/runtime/testing/test_context.hpp"

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

}  // namespace
}  // namespace uampc
