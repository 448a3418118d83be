// sensor_msgs/Image panoramas as the evaluator reads them from the MPC (/mpc/panorama): checked
// (32FC1, little-endian, step, size), then coloured by depth and written as a PNG snapshot every
// panorama_period of sim time, through the in-process test context (the evaluator's own plugin
// library). The MPC only writes panoramas; the evaluator is their one reader.
//
// Input (little-endian): u8 choice of panorama_period, u8 choice of panorama_max_range; u32 width,
// height, step; u8 is_bigendian; u8 encoding length, encoding; i32 stamp sec, u32 nanosec; the
// rest is the pixel data. tests/fuzz/make_corpus.py writes seeds.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>

#include "byte_reader.hpp"
#include "fuzz_input_file.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/runtime/testing/test_context.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace uampc;
  static const char* const periods[] = {"20", "0.05", "0.001", "1000000"};  // within the parameter's bounds
  static const char* const ranges[] = {"40", "0.1", "10000"};
  fuzz::ByteReader in(data, size);
  const std::string period = periods[in.u8() % 4];
  const std::string range = ranges[in.u8() % 3];
  sensor_msgs::msg::Image image;
  image.width(in.u32());
  image.height(in.u32());
  image.step(in.u32());
  image.is_bigendian(in.u8());
  image.encoding(in.shortString());
  image.header().stamp().sec(in.i32());
  image.header().stamp().nanosec(in.u32());
  image.header().frame_id("base_link");
  image.data(in.rest());

  const std::filesystem::path out = fuzz::FuzzDirectory::path() / "run";
  testing::TestOptions options;
  options.output_directory = out.string();
  std::filesystem::create_directories(out);
  {
    testing::TestContext evaluator("evaluator", {{"panorama_period", period}, {"panorama_max_range", range}}, options);
    for (int i = 0; i < 2; ++i) {
      try {
        evaluator.inject("panorama", image);
      } catch (const std::exception&) {  // the runtime's named failure of the component
      }
    }
  }
  std::filesystem::remove_all(out);  // the snapshots: a long run would fill the disk
  return 0;
}
