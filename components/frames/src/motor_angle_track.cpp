#include "uampc/frames/motor_angle_track.hpp"

#include <algorithm>

namespace uampc::frames {

bool MotorAngleTrack::add(const MotorReading& reading) {
  if (!readings_.empty() && reading.time <= readings_.back().time) return false;
  readings_.push_back(reading);
  while (readings_.size() > 2 && readings_.front().time < reading.time - keep_seconds_) {
    readings_.pop_front();
  }
  return true;
}

std::optional<double> MotorAngleTrack::thetaAt(double t) const {
  if (readings_.empty() || t < readings_.front().time || t > readings_.back().time) {
    return std::nullopt;
  }
  // First reading at or after t; readings are sorted by time.
  auto after = std::lower_bound(readings_.begin(), readings_.end(), t,
                                [](const MotorReading& r, double time) { return r.time < time; });
  if (after->time == t || after == readings_.begin()) return after->theta;
  auto before = std::prev(after);
  const double s = (t - before->time) / (after->time - before->time);
  return before->theta + s * (after->theta - before->theta);
}

bool MotorAngleTrack::covers(double t0, double t1) const {
  return !readings_.empty() && readings_.front().time <= t0 && readings_.back().time >= t1;
}

}  // namespace uampc::frames
