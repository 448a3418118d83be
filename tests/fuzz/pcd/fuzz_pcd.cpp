// PCD maps as the map_provider loads them (world: file, map_file: *.pcd): loadMap() checks the
// header and declared sizes, our reader decodes the data (ascii, binary, LZF binary_compressed;
// docs/decisions/pcd-own-reader.md), then non-finite points are skipped and the map downsampled.
// Bad input must end in std::runtime_error naming the file.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz_input_file.hpp"
#include "uampc/world/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = uampc::fuzz::writeInputFile(data, size, "map.pcd");
  try {
    uampc::world::MapLoadOptions options;
    options.voxel_size = 0.5;  // the downsampling path too, as a scene's map_voxel_size asks
    uampc::world::loadMap(path, options);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
