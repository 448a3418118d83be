#include "servo_emulator.hpp"

#include <array>
#include <stdexcept>

#include "emulation/emulated_servo.hpp"
#include "emulation/pseudo_terminal.hpp"

namespace uampc::dynamixel {
namespace {

using Clock = std::chrono::steady_clock;
// How long the server waits for bytes before it advances the motor and the watchdog anyway, and
// looks for stop and unplug/replug requests.
constexpr auto kPollPeriod = std::chrono::milliseconds(2);

EmulatorOptions checked(EmulatorOptions options) {
  if (options.link.empty()) throw std::runtime_error("the emulator needs a link path (EmulatorOptions::link)");
  return options;
}

}  // namespace

ServoEmulator::ServoEmulator(EmulatorOptions options)
    : options_(checked(std::move(options))),
      servo_(std::make_unique<emulation::EmulatedServo>(options_, Clock::now())),
      terminal_(std::make_unique<emulation::PseudoTerminal>(options_.link)),
      server_([this] { serve(); }) {}

ServoEmulator::~ServoEmulator() {
  stopping_ = true;
  server_.join();
  terminal_.reset();  // closes the pty and removes the link
}

void ServoEmulator::corruptReplies(int count) { corrupt_replies_ = count; }

void ServoEmulator::setSilent(bool silent) { silent_ = silent; }

void ServoEmulator::setHardwareError(std::uint8_t bits) {
  std::lock_guard<std::mutex> lock(servo_mutex_);
  servo_->advanceTo(Clock::now());
  servo_->raiseHardwareError(bits);
}

void ServoEmulator::unplug() { requestLinkChange(LinkChange::kUnplug); }

void ServoEmulator::replug() { requestLinkChange(LinkChange::kReplug); }

template <class Read>
auto ServoEmulator::observe(Read read) const {
  std::lock_guard<std::mutex> lock(servo_mutex_);
  servo_->advanceTo(Clock::now());
  return read(*servo_);
}

double ServoEmulator::velocity() const {
  return observe([](const emulation::EmulatedServo& s) { return s.velocity(); });
}
double ServoEmulator::position() const {
  return observe([](const emulation::EmulatedServo& s) { return s.position(); });
}
double ServoEmulator::goalVelocity() const {
  return observe([](const emulation::EmulatedServo& s) { return s.goalVelocity(); });
}
bool ServoEmulator::torqueEnabled() const {
  return observe([](const emulation::EmulatedServo& s) { return s.torqueEnabled(); });
}
bool ServoEmulator::watchdogTripped() const {
  return observe([](const emulation::EmulatedServo& s) { return s.watchdogTripped(); });
}

void ServoEmulator::serve() {
  while (!stopping_) {
    applyLinkChange();
    if (!terminal_) {
      std::this_thread::sleep_for(kPollPeriod);  // unplugged: nothing to hear
    } else if (terminal_->waitReadable(kPollPeriod)) {
      receive();
    }
    std::lock_guard<std::mutex> lock(servo_mutex_);
    servo_->advanceTo(Clock::now());
  }
}

void ServoEmulator::receive() {
  std::array<std::uint8_t, 512> buffer{};
  while (const std::size_t n = terminal_->readSome(buffer.data(), buffer.size())) {
    bytes_received_ += n;
    parser_.feed(buffer.data(), n);
  }
  while (const auto result = parser_.next()) handle(*result);
}

void ServoEmulator::handle(const PacketParser::Result& result) {
  using Kind = PacketParser::Result::Kind;
  if (result.kind == Kind::kMalformed) return;  // no ID to answer, and not a CRC the servo checked
  if (result.kind == Kind::kCrcError) {
    ++corrupt_packets_;
  } else {
    ++packets_;
  }
  if (silent_) return;
  std::optional<Packet> reply;
  std::chrono::microseconds return_delay{};
  {
    std::lock_guard<std::mutex> lock(servo_mutex_);
    const auto now = Clock::now();
    servo_->advanceTo(now);  // the reply reports the motor at this instant
    if (result.kind == Kind::kCrcError) {
      reply = servo_->crcErrorReply();
    } else if (servo_->listensTo(result.packet.id)) {
      reply = servo_->execute(result.packet, now);
    }
    return_delay = servo_->returnDelay();
  }
  if (reply) send(*reply, return_delay);
}

void ServoEmulator::send(const Packet& status, std::chrono::microseconds return_delay) {
  std::vector<std::uint8_t> bytes = encode(status);
  if (takeCorruptReply()) bytes.back() ^= 0xFF;  // the CRC's high byte
  // Return Delay Time: the servo waits before it answers (0 unless the host sets it).
  if (return_delay.count() > 0) std::this_thread::sleep_for(return_delay);
  bytes_sent_ += terminal_->writeSome(bytes);
}

bool ServoEmulator::takeCorruptReply() {
  int remaining = corrupt_replies_;
  while (remaining > 0 && !corrupt_replies_.compare_exchange_weak(remaining, remaining - 1)) {
  }
  return remaining > 0;
}

void ServoEmulator::requestLinkChange(LinkChange change) {
  std::lock_guard<std::mutex> one_caller(link_callers_);
  std::unique_lock<std::mutex> lock(link_mutex_);
  link_change_ = change;
  link_error_ = nullptr;
  link_changed_.wait(lock, [this] { return link_change_ == LinkChange::kNone; });
  if (link_error_) std::rethrow_exception(link_error_);
}

void ServoEmulator::applyLinkChange() {
  std::lock_guard<std::mutex> lock(link_mutex_);
  if (link_change_ == LinkChange::kNone) return;
  try {
    terminal_.reset();  // the host's open port hangs up; the link disappears
    parser_.clear();
    if (link_change_ == LinkChange::kReplug) {
      terminal_ = std::make_unique<emulation::PseudoTerminal>(options_.link);
      std::lock_guard<std::mutex> servo_lock(servo_mutex_);
      servo_->powerCycle(Clock::now());
    }
  } catch (...) {
    link_error_ = std::current_exception();
  }
  link_change_ = LinkChange::kNone;
  link_changed_.notify_all();
}

}  // namespace uampc::dynamixel
