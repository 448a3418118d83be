// PLY maps as the map_provider loads them (world: file, map_file: *.ply): our own reader (ascii,
// binary of either endianness), then a mesh of its faces or a point map. Bad input must end in
// std::runtime_error naming the file.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz_input_file.hpp"
#include "uampc/world/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = uampc::fuzz::writeInputFile(data, size, "map.ply");
  try {
    uampc::world::loadMap(path);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
