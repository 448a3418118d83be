// One X-series servo in velocity control mode on a DYNAMIXEL bus (docs/user/rig.md): identified and
// set up at start, commanded in rad/s, read as a multi-turn angle and a speed stamped on the
// host's clock. Every operation is bounded: a few tries of one reply timeout each.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "uampc/dynamixel/bus.hpp"
#include "uampc/dynamixel/control_table.hpp"

namespace uampc::dynamixel {

struct ServoOptions {
  std::string port;
  int baud_rate = 1000000;
  std::uint8_t id = 1;
  std::string model = "XM430-W350";
  double reply_timeout_s = 0.01;  // per try
  int max_retries = 2;            // further tries after a timeout or a corrupt reply
  double bus_watchdog_s = 0.5;    // the servo stops by itself when the bus is silent this long; 0: off
};

struct ServoState {
  double position = 0;  // rad, multi-turn, unwrapped
  double velocity = 0;  // rad/s
  // When the servo sampled them, on the host's steady clock: the reply's arrival less half the
  // round trip (the servo answers a request as it processes it).
  SteadyClock::time_point stamp;
  double round_trip_s = 0;
  std::uint8_t hardware_error = 0;  // Hardware Error Status (address 70); 0: none
};

// Every try of an operation failed, or the port is gone: the caller decides what to do.
struct BusFault : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Servo {
 public:
  // Opens the port, pings the ID, checks the model and sets the servo up (velocity mode, bus
  // watchdog, torque on); throws SerialError or BusFault with the port, baud rate and ID named.
  explicit Servo(const ServoOptions& options);

  // Goal Velocity, clamped to the servo's Velocity Limit; returns the speed applied, rad/s.
  double setVelocity(double radians_per_second);
  ServoState readState();
  // Opens the port again and repeats the start's identification and set-up.
  void reconnect();
  // Torque off (the motor coasts); used when the bridge stops. Best effort: never throws.
  void release() noexcept;

  double velocityLimit() const { return velocity_limit_; }  // rad/s, read from the servo
  const Model& model() const { return *model_; }
  const Bus& bus() const { return bus_; }
  std::string where() const;  // "ID 1 on /dev/ttyUSB0 at 1000000 baud"

 private:
  Reply request(const Packet& packet, std::size_t expected_params, const char* what);
  std::uint32_t read(Field field, const char* what);
  void write(Field field, std::uint32_t value, const char* what);
  void identify();
  void setUp();
  void rearmWatchdog();
  std::int64_t unwrap(std::int32_t raw);

  ServoOptions options_;
  Bus bus_;
  const Model* model_ = nullptr;
  double velocity_limit_ = 0;
  // Multi-turn angle: Present Position is an int32 that wraps at 2^31 counts and restarts within
  // one turn when the servo is power-cycled.
  std::int64_t turns_counts_ = 0;
  std::int32_t last_raw_ = 0;
  bool have_raw_ = false;
  bool reconnected_ = false;
};

}  // namespace uampc::dynamixel
