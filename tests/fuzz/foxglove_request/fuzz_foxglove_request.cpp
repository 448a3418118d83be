// A Foxglove client's text message as the live viewer's server reads it (libs/foxglove_server,
// parseClientRequest): any bytes must come back as a request or a BadRequest, never an exception,
// a crash or an allocation out of proportion to the input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "uampc/foxglove/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto request = uampc::foxglove::parseClientRequest(std::string(reinterpret_cast<const char*>(data), size));
  if (const auto* bad = std::get_if<uampc::foxglove::BadRequest>(&request)) {
    if (bad->message.empty()) __builtin_trap();  // every refusal says why
  }
  return 0;
}
