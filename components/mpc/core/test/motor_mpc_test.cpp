#include "uampc/mpc/motor_mpc.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic_scenes.hpp"

namespace uampc::mpc {
namespace {

using test::kPi;

// Surrogate of U(theta) = mean - amplitude * cos(theta - best), sampled every 5 degrees from
// theta_start: smallest uncertainty towards `best`.
UncertaintySurrogate cosineSurrogate(double theta_start, double best, double mean = 2.0, double amplitude = 1.0) {
  const int n = 72;
  const double step = UncertaintySurrogate::turnStep(n);
  std::vector<double> samples(n);
  for (int s = 0; s < n; ++s) samples[s] = mean - amplitude * std::cos(theta_start + s * step - best);
  return UncertaintySurrogate(theta_start, step, samples);
}

struct BruteForce {
  Eigen::VectorXd speeds;
  double cost = 1e300;
};

// Exhaustive search over a speed grid for every variable of the horizon.
BruteForce bruteForce(const MotorMpc& mpc, const UncertaintySurrogate& surrogate, double theta, double grid_step) {
  const MotorMpc::Config& c = mpc.config();
  const int n = mpc.variableCount();
  const int levels = static_cast<int>(std::round((c.omega_max - c.omega_min) / grid_step)) + 1;
  BruteForce best;
  Eigen::VectorXd speeds(n);
  std::vector<int> index(n, 0);
  while (true) {
    for (int i = 0; i < n; ++i) speeds[i] = std::min(c.omega_min + index[i] * grid_step, c.omega_max);
    const double f = mpc.cost(surrogate, theta, speeds);
    if (f < best.cost) {
      best.cost = f;
      best.speeds = speeds;
    }
    int i = 0;
    while (i < n && ++index[i] == levels) index[i++] = 0;
    if (i == n) break;
  }
  return best;
}

TEST(MotorMpc, CostUsesTheWeightsAsTheyAre) {
  MotorMpc::Config config;
  config.horizon = 3;
  config.alpha = 7.0;
  config.beta = 0.3;
  const MotorMpc mpc(config);
  const UncertaintySurrogate surrogate = cosineSurrogate(0.2, 1.0);
  Eigen::VectorXd speeds(4);
  speeds << 1.0, 2.0, 5.0, 0.5;
  double theta = 0.2;
  double expected = 0.0;
  for (int i = 0; i < 4; ++i) {
    theta += speeds[i] * config.dt;
    expected += 7.0 * std::pow(surrogate.value(theta), 2) + 0.3 * std::pow(speeds[i] - 3.6, 2);
  }
  EXPECT_NEAR(mpc.cost(surrogate, 0.2, speeds), expected, 1e-9 * expected);
}

// rate_weight adds gamma (omega_i - omega_{i-1})^2, the first against the previous command, and
// nothing when there is none.
TEST(MotorMpc, RateTermTiesEachSpeedToTheOneBefore) {
  MotorMpc::Config config;
  config.horizon = 3;
  const UncertaintySurrogate surrogate = cosineSurrogate(0.2, 1.0);
  Eigen::VectorXd speeds(4);
  speeds << 1.0, 2.0, 5.0, 0.5;
  const double paper = MotorMpc(config).cost(surrogate, 0.2, speeds);
  config.rate_weight = 0.7;
  const MotorMpc mpc(config);
  const double rates_after_first = 0.7 * (1.0 + 9.0 + 20.25);
  EXPECT_NEAR(mpc.cost(surrogate, 0.2, speeds), paper + rates_after_first, 1e-9 * paper);
  EXPECT_NEAR(mpc.cost(surrogate, 0.2, speeds, 4.0), paper + rates_after_first + 0.7 * 9.0, 1e-9 * paper);
  EXPECT_EQ(mpc.residualCount(), 12);
}

// A strong rate term keeps the command near the last one where the paper's F jumps to the
// surrogate's best angle; a weak one changes nothing much.
TEST(MotorMpc, StrongRateWeightHoldsTheLastCommand) {
  MotorMpc::Config config;
  const UncertaintySurrogate surrogate = cosineSurrogate(0.0, 2.5, 2.0, 1.5);
  const double paper = MotorMpc(config).solve(surrogate, 0.0, 3.6).speeds.front();
  config.rate_weight = 1e4;
  const double held = MotorMpc(config).solve(surrogate, 0.0, 3.6).speeds.front();
  EXPECT_GT(std::abs(paper - 3.6), 0.5);  // the paper's F moves away from 3.6 here
  EXPECT_LT(std::abs(held - 3.6), 0.1);
}

TEST(MotorMpc, AnalyticJacobianMatchesFiniteDifferences) {
  MotorMpc::Config config;
  config.horizon = 6;
  config.rate_weight = 0.5;  // the rate rows too
  const MotorMpc mpc(config);
  const UncertaintySurrogate surrogate = cosineSurrogate(-1.0, 2.0, 3.0, 2.0);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(0.0, 7.0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd speeds(mpc.variableCount());
    for (int i = 0; i < speeds.size(); ++i) speeds[i] = uniform(rng);
    Eigen::MatrixXd jacobian;
    mpc.residuals(surrogate, -1.0, speeds, &jacobian, 2.0);
    const double h = 1e-7;
    for (int l = 0; l < speeds.size(); ++l) {
      Eigen::VectorXd plus = speeds;
      Eigen::VectorXd minus = speeds;
      plus[l] += h;
      minus[l] -= h;
      const Eigen::VectorXd fd =
          (mpc.residuals(surrogate, -1.0, plus, nullptr, 2.0) - mpc.residuals(surrogate, -1.0, minus, nullptr, 2.0)) /
          (2 * h);
      // A kink of the surrogate inside +-h makes one row differ; allow for that, not for more.
      int wrong_rows = 0;
      for (int r = 0; r < fd.size(); ++r) {
        wrong_rows += std::abs(fd[r] - jacobian(r, l)) > 1e-4 * (1 + std::abs(fd[r]));
      }
      EXPECT_LE(wrong_rows, 1) << "trial " << trial << " column " << l;
    }
  }
}

TEST(MotorMpc, ZeroAlphaReturnsPreferredSpeed) {
  MotorMpc::Config config;
  config.alpha = 0.0;
  const MotorMpc mpc(config);
  const MotorMpc::Plan plan = mpc.solve(cosineSurrogate(0.0, 1.0, 5.0, 4.0), 0.0);
  ASSERT_EQ(plan.speeds.size(), static_cast<std::size_t>(config.horizon + 1));
  for (double omega : plan.speeds) EXPECT_NEAR(omega, 3.6, 1e-9);
  EXPECT_NEAR(plan.cost, 0.0, 1e-12);
}

TEST(MotorMpc, PreferredSpeedOutsideBoundsIsClamped) {
  MotorMpc::Config config;
  config.alpha = 0.0;
  config.omega_max = 2.0;
  const MotorMpc::Plan plan = MotorMpc(config).solve(cosineSurrogate(0.0, 1.0), 0.0);
  for (double omega : plan.speeds) EXPECT_NEAR(omega, 2.0, 1e-9);
}

// Small horizons: the Ceres solution is as good as an exhaustive grid search, and close to it.
// Tolerances: U' is piecewise linear, so F has ridges along theta_i = sample angle; a smooth
// solver can stop on such a ridge a little short of the optimum (seen: 1.5e-5 relative cost, 0.19
// rad/s on the last speed of the horizon). The executed first speed is held to 0.05 rad/s.
TEST(MotorMpc, MatchesBruteForceOnSmallHorizons) {
  struct Case {
    int horizon;
    double alpha;
    double best_offset;  // where U is smallest, relative to theta_now
    double grid;
  };
  const Case cases[] = {{0, 10.0, 0.4, 0.001}, {0, 1000.0, 0.2, 0.001}, {1, 10.0, 0.5, 0.01}, {1, 1000.0, 0.9, 0.01},
                        {1, 30.0, -0.6, 0.01}, {1, 100.0, 2.5, 0.01},   {3, 50.0, 0.7, 0.2}};
  for (const Case& c : cases) {
    MotorMpc::Config config;
    config.horizon = c.horizon;
    config.alpha = c.alpha;
    const MotorMpc mpc(config);
    const double theta_now = 0.3;
    const UncertaintySurrogate surrogate = cosineSurrogate(theta_now, theta_now + c.best_offset);
    const MotorMpc::Plan plan = mpc.solve(surrogate, theta_now);
    const BruteForce brute = bruteForce(mpc, surrogate, theta_now, c.grid);
    SCOPED_TRACE("horizon " + std::to_string(c.horizon) + " alpha " + std::to_string(c.alpha) + " offset " +
                 std::to_string(c.best_offset));
    EXPECT_LE(plan.cost, brute.cost + 1e-4 * (1 + brute.cost));
    EXPECT_LT(plan.cost, plan.initial_cost + 1e-12);
    if (c.grid <= 0.01) {  // fine grid: the minimisers agree too
      EXPECT_NEAR(plan.speeds[0], brute.speeds[0], 0.05);
      for (int i = 1; i < mpc.variableCount(); ++i) {
        EXPECT_NEAR(plan.speeds[i], brute.speeds[i], 0.25) << "speed " << i;
      }
    }
  }
}

TEST(MotorMpc, BoundsHold) {
  MotorMpc::Config config;
  config.omega_min = 0.5;
  config.omega_max = 5.0;
  const MotorMpc mpc(config);
  // Far-ahead minimum: wants to rush; minimum just behind: wants to stop.
  for (double offset : {3.0, 2.0, -0.3, -0.05, 0.6}) {
    const MotorMpc::Plan plan = mpc.solve(cosineSurrogate(0.0, offset, 3.0, 2.5), 0.0);
    for (double omega : plan.speeds) {
      EXPECT_GE(omega, config.omega_min);
      EXPECT_LE(omega, config.omega_max);
    }
    if (offset == 3.0) {
      EXPECT_NEAR(plan.speeds.front(), config.omega_max, 1e-6);
    }
    if (offset == -0.05) {
      EXPECT_NEAR(plan.speeds.front(), config.omega_min, 1e-6);
    }
  }
}

TEST(MotorMpc, PlanReportsAnglesAndPredictedUncertainty) {
  MotorMpc::Config config;
  config.horizon = 4;
  const MotorMpc mpc(config);
  const UncertaintySurrogate surrogate = cosineSurrogate(7.0, 8.0);
  const MotorMpc::Plan plan = mpc.solve(surrogate, 7.0);
  ASSERT_EQ(plan.angles.size(), 5U);
  ASSERT_EQ(plan.predicted_uncertainty.size(), 5U);
  double theta = 7.0;
  for (int i = 0; i < 5; ++i) {
    theta += plan.speeds[i] * config.dt;
    EXPECT_NEAR(plan.angles[i], theta, 1e-12);
    EXPECT_NEAR(plan.predicted_uncertainty[i], surrogate.value(theta), 1e-12);
  }
  EXPECT_GT(plan.iterations, 0);
}

TEST(MotorMpc, RejectsInvalidConfig) {
  MotorMpc::Config config;
  config.omega_min = 3.0;
  config.omega_max = 3.0;
  EXPECT_THROW(MotorMpc{config}, std::invalid_argument);
  config = {};
  config.dt = 0.0;
  EXPECT_THROW(MotorMpc{config}, std::invalid_argument);
  config = {};
  config.alpha = -1.0;
  EXPECT_THROW(MotorMpc{config}, std::invalid_argument);
}

}  // namespace
}  // namespace uampc::mpc
