#include "uampc/dynamixel/bus.hpp"

#include <utility>

namespace uampc::dynamixel {

Bus::Bus(std::string port, int baud_rate, std::chrono::microseconds reply_timeout)
    : path_(std::move(port)), baud_rate_(baud_rate), reply_timeout_(reply_timeout) {
  reopen();
}

void Bus::reopen() {
  port_.reset();
  parser_.clear();
  port_ = std::make_unique<SerialPort>(path_, baud_rate_);
}

Reply Bus::transact(const Packet& request, std::size_t expected_params) {
  ++counters_.transactions;
  Reply reply;
  reply.sent = SteadyClock::now();
  if (!port_) {
    ++counters_.port_errors;
    reply.outcome = Reply::Outcome::kPortError;
    reply.detail = "serial port " + path_ + " is closed";
    return reply;
  }
  try {
    // A reply that came after its request had timed out must not pass for this one's.
    port_->discardInput();
    parser_.clear();
    const std::vector<std::uint8_t> bytes = encode(request);
    reply.sent = SteadyClock::now();
    port_->write(bytes);
    counters_.bytes_sent += bytes.size();
    return receive(request.id, expected_params, std::move(reply));
  } catch (const SerialError& e) {
    ++counters_.port_errors;
    port_.reset();  // reopen() brings it back
    reply.outcome = Reply::Outcome::kPortError;
    reply.detail = e.what();
    return reply;
  }
}

Reply Bus::receive(std::uint8_t id, std::size_t expected_params, Reply reply) {
  const auto deadline = reply.sent + reply_timeout_;
  std::uint8_t buffer[256];
  bool corrupt = false;
  for (;;) {
    while (auto result = parser_.next()) {
      if (result->kind != PacketParser::Result::Kind::kPacket) {
        corrupt = true;
        continue;
      }
      // A half-duplex adapter may echo our own request; only a status from the addressed ID counts.
      if (result->packet.instruction != instruction::kStatus || result->packet.id != id) continue;
      const auto& params = result->packet.params;
      const bool error = !params.empty() && (params[0] & ~kAlertBit) != 0;
      if (expected_params != 0 && params.size() != expected_params && !error) {
        ++counters_.stale;
        continue;
      }
      reply.received = SteadyClock::now();
      reply.outcome = Reply::Outcome::kOk;
      reply.status = std::move(result->packet);
      return reply;
    }
    // One request, one status: after a corrupt one nothing else is coming.
    if (corrupt) break;
    const std::size_t n = port_->read(buffer, sizeof buffer, deadline);
    if (n == 0) break;
    counters_.bytes_received += n;
    parser_.feed(buffer, n);
  }
  reply.received = SteadyClock::now();
  if (corrupt) {
    ++counters_.corrupt;
    reply.outcome = Reply::Outcome::kCorrupt;
    reply.detail = "corrupt status packet (CRC or length mismatch)";
  } else {
    ++counters_.timeouts;
    reply.outcome = Reply::Outcome::kTimeout;
    reply.detail = "no status packet within " + std::to_string(reply_timeout_.count()) + " us";
  }
  return reply;
}

}  // namespace uampc::dynamixel
