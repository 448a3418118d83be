#include "uampc/mpc/uncertainty_surrogate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic_scenes.hpp"

namespace uampc::mpc {
namespace {

using test::kPi;

UncertaintySurrogate randomSurrogate(double theta_start, int count = 72) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(0.5, 50.0);
  std::vector<double> samples(count);
  for (double& u : samples) u = uniform(rng);
  return UncertaintySurrogate(theta_start, UncertaintySurrogate::turnStep(count), samples);
}

TEST(UncertaintySurrogate, EqualsSamplesAtSampleAnglesOnAnyTurn) {
  const UncertaintySurrogate surrogate = randomSurrogate(1.234);
  for (int s = 0; s < surrogate.count(); ++s) {
    for (int turns : {-3, -1, 0, 1, 5, 40}) {
      const double theta = 1.234 + s * surrogate.step() + turns * 2.0 * kPi;
      EXPECT_NEAR(surrogate.value(theta), surrogate.samples()[s], 1e-9) << "s=" << s << " turns=" << turns;
    }
  }
}

TEST(UncertaintySurrogate, LinearBetweenSamplesIncludingTheWrap) {
  const UncertaintySurrogate surrogate = randomSurrogate(-0.5);
  const int n = surrogate.count();
  for (int s = 0; s < n; ++s) {
    const double u0 = surrogate.samples()[s];
    const double u1 = surrogate.samples()[(s + 1) % n];  // s = n - 1 crosses the 2 pi wrap
    for (double f : {0.1, 0.25, 0.5, 0.9}) {
      for (int turns : {-2, 0, 3}) {
        const double theta = -0.5 + (s + f) * surrogate.step() + turns * 2.0 * kPi;
        EXPECT_NEAR(surrogate.value(theta), (1 - f) * u0 + f * u1, 1e-9);
      }
    }
  }
}

TEST(UncertaintySurrogate, WrapSegmentJoinsLastAndFirstSample) {
  const UncertaintySurrogate surrogate(0.0, UncertaintySurrogate::turnStep(4), {1.0, 2.0, 3.0, 9.0});
  // Between 3 pi / 2 (U = 9) and 2 pi (U = 1 again).
  EXPECT_NEAR(surrogate.value(1.75 * kPi), 5.0, 1e-12);
  EXPECT_NEAR(surrogate.slope(1.75 * kPi), -8.0 / (0.5 * kPi), 1e-12);
  // Just below theta_start is the same segment.
  EXPECT_NEAR(surrogate.value(-0.25 * kPi), 5.0, 1e-12);
  EXPECT_NEAR(surrogate.value(2.0 * kPi), 1.0, 1e-12);
}

TEST(UncertaintySurrogate, SlopeMatchesFiniteDifference) {
  const UncertaintySurrogate surrogate = randomSurrogate(2.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-30.0, 30.0);
  const double h = 1e-6;
  int checked = 0;
  while (checked < 500) {
    const double theta = uniform(rng);
    // Stay away from the kinks, where the one-sided slopes differ.
    const double position = (theta - 2.0) / surrogate.step();
    const double fraction = position - std::floor(position);
    if (fraction < 1e-3 || fraction > 1 - 1e-3) continue;
    const double fd = (surrogate.value(theta + h) - surrogate.value(theta - h)) / (2 * h);
    EXPECT_NEAR(surrogate.slope(theta), fd, 1e-5 * (1 + std::abs(fd)));
    double value = 0.0;
    double slope = 0.0;
    surrogate.evaluate(theta, &value, &slope);
    EXPECT_EQ(value, surrogate.value(theta));
    EXPECT_EQ(slope, surrogate.slope(theta));
    ++checked;
  }
}

TEST(UncertaintySurrogate, SamplesPerTurnRoundsToAWholeTurn) {
  EXPECT_EQ(UncertaintySurrogate::samplesPerTurn(5.0 * kPi / 180.0), 72);
  EXPECT_EQ(UncertaintySurrogate::samplesPerTurn(5.01 * kPi / 180.0), 72);
  EXPECT_NEAR(UncertaintySurrogate::turnStep(72) * 72, 2.0 * kPi, 1e-12);
  EXPECT_THROW(UncertaintySurrogate::samplesPerTurn(0.0), std::invalid_argument);
}

TEST(UncertaintySurrogate, RejectsInconsistentInput) {
  EXPECT_THROW(UncertaintySurrogate(0.0, 0.1, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(UncertaintySurrogate(0.0, 1.0, {}), std::invalid_argument);
  EXPECT_THROW(UncertaintySurrogate(0.0, kPi, {1.0, std::nan("")}), std::invalid_argument);
  EXPECT_NO_THROW(UncertaintySurrogate(0.0, kPi, {1.0, 2.0}));
}

TEST(UncertaintySurrogate, NanAngleGivesNanNotGarbage) {
  const UncertaintySurrogate surrogate = randomSurrogate(0.0);
  EXPECT_TRUE(std::isnan(surrogate.value(std::nan(""))));
}

}  // namespace
}  // namespace uampc::mpc
