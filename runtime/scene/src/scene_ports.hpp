// The scene's graph checked once every component is read: port references ("component/port")
// resolved to topics, and every topic's ports compared (docs/user/scenes.md, "Topics").
#pragma once

#include <map>
#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"

namespace uampc {

// A port mapped to another component's port ("component/port").
struct PortReference {
  std::size_t instance;  // index in Scene::components
  std::string port;
  std::string target;  // "component/port"
  SourceLocation location;
};

// "file:line:column: error: message" (or warning).
std::string diagnostic(const SourceLocation& where, const char* severity, const std::string& message);

// Gives every referring port the topic at the end of its chain of references, however long and in
// whatever order the links were written; errors for unknown targets and for cycles.
void resolvePortReferences(Scene& scene, const std::vector<PortReference>& references,
                           std::vector<std::string>& errors);

// Adds to every component that decides ports from the scene (ComponentSpec::scenePorts, e.g. a
// recorder or a player) the ports it asks for; errors for what it rejects.
void resolveScenePorts(Scene& scene, std::vector<std::string>& errors);

// Type clashes (errors), inputs no component writes and outputs nobody reads (see the .cpp for
// which is an error). `remapped` holds "instance.port" -> where the scene set that port's topic,
// `unused_inputs` each topic of Scene::unused_inputs -> where the scene lists it.
void checkConnections(Scene& scene, const std::map<std::string, SourceLocation>& remapped,
                      const std::map<std::string, SourceLocation>& unused_inputs, std::vector<std::string>& errors);

}  // namespace uampc
