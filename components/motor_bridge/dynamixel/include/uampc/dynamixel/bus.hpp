// One DYNAMIXEL bus: a request, then its status packet, within a reply timeout. Half duplex: one
// transaction at a time, each stamped on the host's clock.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "uampc/dynamixel/protocol.hpp"
#include "uampc/dynamixel/serial_port.hpp"

namespace uampc::dynamixel {

struct Reply {
  enum class Outcome {
    kOk,         // a status packet from the addressed ID with a valid CRC (its error byte may still be set)
    kTimeout,    // no complete status packet within the reply timeout
    kCorrupt,    // bytes arrived, but the packet's CRC or length was wrong
    kPortError,  // the port failed: the adapter or cable is gone
  };
  Outcome outcome = Outcome::kTimeout;
  Packet status;                     // kOk only
  SteadyClock::time_point sent;      // before the request was written
  SteadyClock::time_point received;  // when the reply was complete
  std::string detail;                // what went wrong, for the log
  bool ok() const { return outcome == Outcome::kOk; }
  std::uint8_t error() const { return status.params.empty() ? 0 : status.params[0]; }
};

struct BusCounters {
  std::uint64_t transactions = 0, timeouts = 0, corrupt = 0, port_errors = 0, stale = 0;
  std::uint64_t bytes_sent = 0, bytes_received = 0;
};

class Bus {
 public:
  // Opens the port (throws SerialError naming it).
  Bus(std::string port, int baud_rate, std::chrono::microseconds reply_timeout);

  // expected_params: the parameter count of this request's status packet (error byte included), or
  // 0 for any. A status of another size without an error is a late reply to an earlier request
  // (half duplex cannot tell them apart otherwise): it is skipped, and counted as stale.
  Reply transact(const Packet& request, std::size_t expected_params = 0);
  // Closes and opens the port again (a USB adapter that came back); throws SerialError.
  void reopen();
  bool isOpen() const { return port_ != nullptr; }

  const std::string& port() const { return path_; }
  int baudRate() const { return baud_rate_; }
  const BusCounters& counters() const { return counters_; }

 private:
  Reply receive(std::uint8_t id, std::size_t expected_params, Reply reply);

  std::string path_;
  int baud_rate_;
  std::chrono::microseconds reply_timeout_;
  std::unique_ptr<SerialPort> port_;
  PacketParser parser_;
  BusCounters counters_;
};

}  // namespace uampc::dynamixel
