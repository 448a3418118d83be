// Periodic piecewise-linear surrogate U'(theta) of the uncertainty and its slope (Eqs. 9 and 10).
//
// U is sampled once per control step at theta_s = theta_start + s * step, s = 0 .. N - 1, with
// N * step = 2 pi. Between two samples the surrogate is the straight line through them (Eq. 9),
//
//   U'(theta) = U_s + (U_{s+1} - U_s) / step * (theta - theta_s),   s = floor((theta - theta_start) / step) mod N,
//
// with U_N = U_0 (periodic in 2 pi), and its analytic slope is the slope of that segment (Eq. 10),
//
//   dU'/dtheta = (U_{s+1} - U_s) / step.
//
// theta may be any real number (multi-turn encoder angle, or below theta_start). At a sample
// angle the value is U_s exactly and the slope is that of the segment to the right.
#pragma once

#include <vector>

namespace uampc::mpc {

class UncertaintySurrogate {
 public:
  // count() * step must equal 2 pi (to 1e-9 rad); throws std::invalid_argument otherwise, or when
  // samples is empty or holds a non-finite value.
  UncertaintySurrogate(double theta_start, double step, std::vector<double> samples);

  // The number of samples that make one turn when sampling every approximately `step` radians;
  // use with turnStep(): count = samplesPerTurn(5 deg) = 72, step = 2 pi / 72.
  static int samplesPerTurn(double step);
  static double turnStep(int count);

  double value(double theta) const;
  double slope(double theta) const;
  void evaluate(double theta, double* value, double* slope) const;

  double thetaStart() const { return theta_start_; }
  double step() const { return step_; }
  int count() const { return static_cast<int>(samples_.size()); }
  const std::vector<double>& samples() const { return samples_; }

 private:
  double theta_start_;
  double step_;
  std::vector<double> samples_;
};

}  // namespace uampc::mpc
