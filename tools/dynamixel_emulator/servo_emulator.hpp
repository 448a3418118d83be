// An emulated DYNAMIXEL X-series servo (XM430-like) on a pseudo-terminal: the motor bridge's tests
// and users without hardware open its link path as they would open a USB adapter's port, and speak
// Protocol 2.0 to it. It behaves as the X-series e-manual describes the real servo, for the
// instructions PING, READ, WRITE and REBOOT, and lets a test inject the faults a real bus has.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "emulator_options.hpp"
#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel {

namespace emulation {
class EmulatedServo;
class PseudoTerminal;
}  // namespace emulation

class ServoEmulator {  // starts serving in the constructor (own thread), stops in the destructor
 public:
  explicit ServoEmulator(EmulatorOptions options);  // throws std::runtime_error with a clear message
  ~ServoEmulator();
  ServoEmulator(const ServoEmulator&) = delete;
  ServoEmulator& operator=(const ServoEmulator&) = delete;

  const std::string& port() const { return options_.link; }

  // Fault injection (thread-safe):
  void corruptReplies(int count);  // the next `count` status packets go out with a wrong CRC
  // Receives (and counts) but neither executes nor answers: a wrong ID or a dead servo.
  void setSilent(bool silent);
  // Hardware Error Status (70) |= bits: torque off, every status has kAlertBit. 0 clears nothing:
  // only REBOOT clears it, as on the real servo.
  void setHardwareError(std::uint8_t bits);
  void unplug();  // closes the pty master and removes the link: the host's reads/writes fail
  // A new pty and the link recreated; RAM reset as a power cycle (torque off, goal 0, position
  // within one turn, bus watchdog 0, hardware error cleared). Throws if the pty cannot be made.
  void replug();

  // Observation (thread-safe), at the instant of the call:
  double velocity() const;      // rad/s, true
  double position() const;      // rad, true, multi-turn (not wrapped)
  double goalVelocity() const;  // rad/s
  bool torqueEnabled() const;
  bool watchdogTripped() const;
  std::uint64_t packetsReceived() const { return packets_; }                 // intact packets, any ID
  std::uint64_t corruptPacketsReceived() const { return corrupt_packets_; }  // CRC mismatches
  std::uint64_t bytesReceived() const { return bytes_received_; }
  std::uint64_t bytesSent() const { return bytes_sent_; }

 private:
  enum class LinkChange { kNone, kUnplug, kReplug };

  void serve();
  void receive();
  void handle(const PacketParser::Result& result);
  void send(const Packet& status, std::chrono::microseconds return_delay);
  bool takeCorruptReply();
  void requestLinkChange(LinkChange change);
  void applyLinkChange();
  template <class Read>
  auto observe(Read read) const;

  const EmulatorOptions options_;
  mutable std::mutex servo_mutex_;
  std::unique_ptr<emulation::EmulatedServo> servo_;  // guarded by servo_mutex_
  // After the constructor, only the server thread touches the terminal and the parser.
  std::unique_ptr<emulation::PseudoTerminal> terminal_;
  PacketParser parser_;

  std::atomic<bool> stopping_{false};
  std::atomic<bool> silent_{false};
  std::atomic<int> corrupt_replies_{0};
  std::atomic<std::uint64_t> packets_{0}, corrupt_packets_{0}, bytes_received_{0}, bytes_sent_{0};

  // unplug()/replug() ask the server thread, which owns the terminal, and wait until it is done.
  std::mutex link_callers_;  // one request at a time
  std::mutex link_mutex_;
  std::condition_variable link_changed_;
  LinkChange link_change_ = LinkChange::kNone;  // guarded by link_mutex_
  std::exception_ptr link_error_;               // guarded by link_mutex_

  std::thread server_;  // last: started once everything above exists
};

}  // namespace uampc::dynamixel
