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
  std::size_t cursor = readings_.size();
  return thetaAt(t, cursor);
}

std::optional<double> MotorAngleTrack::thetaAt(double t, std::size_t& cursor) const {
  if (readings_.empty() || t < readings_.front().time || t > readings_.back().time) {
    return std::nullopt;
  }
  // First reading at or after t; readings are sorted by time.
  const bool cursor_holds =
      cursor < readings_.size() && readings_[cursor].time >= t && (cursor == 0 || readings_[cursor - 1].time < t);
  if (!cursor_holds) {
    const auto after = std::lower_bound(readings_.begin(), readings_.end(), t,
                                        [](const MotorReading& r, double time) { return r.time < time; });
    cursor = static_cast<std::size_t>(after - readings_.begin());
  }
  const MotorReading& after = readings_[cursor];
  if (after.time == t || cursor == 0) return after.theta;
  const MotorReading& before = readings_[cursor - 1];
  const double s = (t - before.time) / (after.time - before.time);
  return before.theta + s * (after.theta - before.theta);
}

std::optional<double> MotorAngleTrack::omegaAt(double t) const {
  if (readings_.empty() || t < readings_.front().time || t > readings_.back().time) return std::nullopt;
  const auto after = std::lower_bound(readings_.begin(), readings_.end(), t,
                                      [](const MotorReading& r, double time) { return r.time < time; });
  if (after->time == t || after == readings_.begin()) return after->omega;
  const MotorReading& before = *(after - 1);
  const double s = (t - before.time) / (after->time - before.time);
  return before.omega + s * (after->omega - before.omega);
}

bool MotorAngleTrack::covers(double t0, double t1) const {
  return !readings_.empty() && readings_.front().time <= t0 && readings_.back().time >= t1;
}

}  // namespace uampc::frames
