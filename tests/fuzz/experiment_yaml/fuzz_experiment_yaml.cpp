// Experiment files as `uampc experiment` reads them: loadExperiment() (names, seeds, scenes,
// controllers, ${data_dir}, overrides) and the run plan it makes of them (planRuns). Any
// ExperimentError is a correct answer.
#include <cstddef>
#include <cstdint>

#include "experiment/experiment_file.hpp"
#include "experiment/backends/experiment_runner.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = uampc::fuzz::writeInputFile(data, size, "experiment.yaml");
  try {
    const auto experiment = uampc::app::loadExperiment(path, {{"data_dir", "/nonexistent/data"}});
    uampc::app::planRuns(experiment, {"clock.duration=1"});
  } catch (const uampc::app::ExperimentError&) {
  }
  return 0;
}
