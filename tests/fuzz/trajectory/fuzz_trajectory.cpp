// Trajectory files: the same bytes as an MCD CSV and as a TUM file through map_provider's readers
// (readTrajectory with the options the map_provider uses: forMcd() for .csv, poses from t = 0), and
// as a TUM file through the evaluator's reader (readTumTrajectory, `uampc experiment`'s results).
// Every reader documents std::runtime_error naming file and line for bad input.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz_input_file.hpp"
#include "uampc/evaluator/tum_trajectory.hpp"
#include "uampc/world/trajectory_io.hpp"

namespace {

template <typename Read>
void expectRuntimeErrorOnly(Read read) {
  try {
    read();
  } catch (const std::runtime_error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace uampc;
  const std::string csv = fuzz::writeInputFile(data, size, "trajectory.csv");
  const std::string tum = fuzz::writeInputFile(data, size, "trajectory.tum");
  expectRuntimeErrorOnly([&] {
    world::TrajectoryReadOptions options = world::TrajectoryReadOptions::forMcd();
    options.start_at_zero = true;
    world::readTrajectory(csv, options);
  });
  expectRuntimeErrorOnly([&] {
    world::TrajectoryReadOptions options;
    options.start_at_zero = true;
    world::readTrajectory(tum, options);
  });
  expectRuntimeErrorOnly([&] { evaluator::readTumTrajectory(tum); });
  return 0;
}
