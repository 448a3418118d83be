#include "uampc/mpc/uncertainty_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "synthetic_scenes.hpp"

namespace uampc::mpc {
namespace {

using test::kPi;

TEST(UncertaintyFilter, WeightOneReturnsEachStepsSamples) {
  UncertaintyFilter filter(1.0);
  const std::vector<double> a = {1.0, 2.0, 3.0, 4.0}, b = {5.0, 6.0, 7.0, 8.0};
  EXPECT_EQ(filter.apply(0.0, kPi / 2, a), a);
  EXPECT_EQ(filter.apply(0.0, kPi / 2, b), b);
}

TEST(UncertaintyFilter, AveragesPerMotorAngleWhereverATurnStarts) {
  UncertaintyFilter filter(0.25);
  const double step = kPi / 2;  // four bins: 0, 90, 180, 270 degrees
  // First step from angle 0: the averages start at the samples.
  EXPECT_EQ(filter.apply(0.0, step, {10.0, 20.0, 30.0, 40.0}), (std::vector<double>{10.0, 20.0, 30.0, 40.0}));
  // The next turn starts at 180 degrees plus a bit and one turn more (multi-turn encoder):
  // sample 0 belongs to the 180-degree bin, sample 1 to 270, 2 to 0, 3 to 90.
  const std::vector<double> out = filter.apply(3 * kPi + 0.1, step, {0.0, 0.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(out[0], 0.75 * 30.0);
  EXPECT_DOUBLE_EQ(out[1], 0.75 * 40.0);
  EXPECT_DOUBLE_EQ(out[2], 0.75 * 10.0);
  EXPECT_DOUBLE_EQ(out[3], 0.75 * 20.0);
  // Negative angles map to the same bins.
  const std::vector<double> back = filter.apply(-kPi / 2, step, {4.0, 4.0, 4.0, 4.0});  // 270, 0, 90, 180
  EXPECT_DOUBLE_EQ(back[1], 0.75 * 0.75 * 10.0 + 0.25 * 4.0);
}

TEST(UncertaintyFilter, ANewSampleCountStartsOver) {
  UncertaintyFilter filter(0.5);
  filter.apply(0.0, kPi, {2.0, 4.0});
  EXPECT_EQ(filter.apply(0.0, kPi / 2, {1.0, 1.0, 1.0, 1.0}), (std::vector<double>{1.0, 1.0, 1.0, 1.0}));
}

TEST(UncertaintyFilter, RefusesAWeightOutsideZeroToOne) {
  EXPECT_THROW(UncertaintyFilter(0.0), std::invalid_argument);
  EXPECT_THROW(UncertaintyFilter(1.5), std::invalid_argument);
  EXPECT_THROW(UncertaintyFilter(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace uampc::mpc
