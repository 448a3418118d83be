// A short history of encoder readings, interpolated at any time inside it.
//
// Eq. 1 needs theta at each point's own time; encoder states arrive at their own rate (200 Hz by
// default), so theta(t) is interpolated linearly between the two readings around t. Angles are
// multi-turn (unwrapped), as the motor bridge publishes them, so interpolation never crosses a wrap.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

namespace uampc::frames {

struct MotorReading {
  double time = 0.0;   // s
  double theta = 0.0;  // rad, multi-turn
  double omega = 0.0;  // rad/s
};

class MotorAngleTrack {
 public:
  // keep_seconds: readings older than the newest minus keep_seconds are dropped.
  explicit MotorAngleTrack(double keep_seconds = 2.0) : keep_seconds_(keep_seconds) {}

  // Readings must come in increasing time; an older or equal one is refused (returns false).
  bool add(const MotorReading& reading);

  // theta at time t, or nothing when t lies outside the stored readings.
  std::optional<double> thetaAt(double t) const;
  // The same, for many times in (nearly) increasing order, as the points of a scan come: cursor
  // keeps the index of the reading found last time (any value to start), and a time between the
  // same two readings needs no search. A scan has ~1000 points per encoder interval.
  std::optional<double> thetaAt(double t, std::size_t& cursor) const;

  // The motor's rate at time t, interpolated between the readings' velocities (not differentiated
  // from the angles, which the encoder quantises), or nothing outside the stored readings.
  std::optional<double> omegaAt(double t) const;

  // True when the readings span [t0, t1].
  bool covers(double t0, double t1) const;

  bool empty() const { return readings_.empty(); }
  std::size_t size() const { return readings_.size(); }
  const MotorReading& newest() const { return readings_.back(); }
  const MotorReading& oldest() const { return readings_.front(); }

 private:
  double keep_seconds_;
  std::deque<MotorReading> readings_;
};

}  // namespace uampc::frames
