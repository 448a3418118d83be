// What the motor bridge drives: the simulated motor or a real one on a bus. The bridge itself keeps
// what is common (the command timeout, the safe speed, the published JointState).
#pragma once

#include <optional>

#include "uampc/runtime/time.hpp"

namespace uampc {

struct MotorReading {
  double position = 0;  // rad, multi-turn (the encoder angle theta)
  double velocity = 0;  // rad/s (omega)
  Time stamp;           // when the encoder was read, on the scene's clock
};

class MotorBackend {
 public:
  virtual ~MotorBackend() = default;
  // The speed to drive at from `now` on, rad/s (the bridge has checked it is finite).
  virtual void command(double omega, Time now) = 0;
  // The encoder at `now`; nothing when it cannot be read (a bus fault), so that no stale state is
  // published as a fresh one.
  virtual std::optional<MotorReading> read(Time now) = 0;
};

}  // namespace uampc
