// U samples averaged over control steps, per absolute motor angle: a controller option meant to
// calm UA-MPC's command (docs/results/controller-options.md).
//
// Every control step samples U over one turn from the current motor angle. The filter keeps one
// exponential average per angle bin of the turn (bin k holds the angle k * step mod 2 pi; a
// sample goes to the nearest bin) and returns the averages in the samples' order:
//
//   F_k <- (1 - w) F_k + w U_s   (F_k = U_s the first time),   w = weight.
//
// A departure from the paper, which uses each step's samples as they are; it is off (weight 1)
// unless a scene asks for it. Measured open loop and closed loop, and not adopted.
#pragma once

#include <vector>

namespace uampc::mpc {

class UncertaintyFilter {
 public:
  // weight in (0, 1]; 1 returns every step's samples unchanged. Throws std::invalid_argument
  // otherwise.
  explicit UncertaintyFilter(double weight = 1.0);

  // samples[s] is U at theta_start + s * step, and samples.size() * step is one turn. Returns the
  // filtered samples in the same order (the vector it was given, filtered in place: with weight 1
  // nothing is copied). A different number of samples per turn starts over.
  std::vector<double> apply(double theta_start, double step, std::vector<double> samples);

  double weight() const { return weight_; }

 private:
  double weight_;
  std::vector<double> averages_;  // per angle bin; empty until the first step
};

}  // namespace uampc::mpc
