// What `uampc launch --out DIR` records of a run when it starts, from the one resolved Scene it
// runs: DIR/scene.yaml, the scene as a scene file (after extends:, --set and the defaults, every
// value written out), which `uampc launch` runs again to reproduce the run; and DIR/run_info.json
// (run_files/run_info.hpp: the scene launched, the overrides, seed, versions, every parameter),
// which the evaluator copies into metrics.json.
#pragma once

#include <string>

#include "uampc/runtime/launcher.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc {

// Every top-level key, the clock, the rig and every component with its type, process and every
// parameter (rig parameters under rig:); topics only where they differ from the port's default
// (an input remapped by hand to a topic nobody writes is an error, on its default topic only a
// warning). Paths are absolute, numbers the shortest text that reads back as the same value.
std::string resolvedSceneYaml(const Scene& scene);

// Writes both files into options.output_directory; throws std::runtime_error naming the file.
void writeRunRecord(const Scene& scene, const LaunchOptions& options);

}  // namespace uampc
