#include "uampc/lo/adaptive_process_noise.hpp"

#include <algorithm>

namespace uampc::lo {

AdaptiveProcessNoise::AdaptiveProcessNoise(double window, ProcessNoise floor, ProcessNoise ceiling)
    : window_(window),
      // A floor above its ceiling would leave std::clamp undefined: the ceiling wins.
      floor_{std::min(floor.linear, ceiling.linear), std::min(floor.angular, ceiling.angular)},
      ceiling_(ceiling) {}

void AdaptiveProcessNoise::add(double time, double dt, const Eigen::Vector3d& dv, const Eigen::Vector3d& dw) {
  corrections_.push_back({time, dt, dv.squaredNorm(), dw.squaredNorm()});
  while (!corrections_.empty() && corrections_.front().time <= time - window_) corrections_.pop_front();
}

ProcessNoise AdaptiveProcessNoise::estimate() const {
  double duration = 0.0, dv2 = 0.0, dw2 = 0.0;
  for (const Correction& c : corrections_) {
    duration += c.dt;
    dv2 += c.dv2;
    dw2 += c.dw2;
  }
  if (!(duration >= 0.5 * window_)) return ceiling_;
  // A velocity random walk of density q changes each of 3 axes by variance q dt over dt.
  return {std::clamp(dv2 / (3.0 * duration), floor_.linear, ceiling_.linear),
          std::clamp(dw2 / (3.0 * duration), floor_.angular, ceiling_.angular)};
}

}  // namespace uampc::lo
