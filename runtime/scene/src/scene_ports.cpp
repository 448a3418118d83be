#include "scene_ports.hpp"

#include <algorithm>
#include <set>

#include "uampc/runtime/edit_distance.hpp"

namespace uampc {

std::string diagnostic(const SourceLocation& where, const char* severity, const std::string& message) {
  return where.str() + ": " + severity + ": " + message;
}

namespace {

std::size_t indexOf(const Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.components.size(); ++i) {
    if (scene.components[i].name == name) return i;
  }
  return scene.components.size();
}

std::string describe(const Scene& scene, const PortReference& r) {
  return scene.components[r.instance].name + "." + r.port + " = " + r.target + " (" + r.location.str() + ")";
}

}  // namespace

void resolvePortReferences(Scene& scene, const std::vector<PortReference>& references,
                           std::vector<std::string>& errors) {
  std::map<std::pair<std::size_t, std::string>, const PortReference*> referring;
  for (const auto& r : references) referring[{r.instance, r.port}] = &r;
  std::set<const PortReference*> settled;  // resolved, or its error reported
  // Following each chain to its end is the fixed point of "replace every reference by its
  // target's topic until nothing changes", reached directly, and it finds cycles on the way.
  for (const auto& start : references) {
    if (settled.count(&start)) continue;
    std::vector<const PortReference*> chain;
    const PortReference* link = &start;
    while (true) {
      const auto seen = std::find(chain.begin(), chain.end(), link);
      if (seen != chain.end() || settled.count(link)) {
        if (seen != chain.end()) {
          std::string cycle;
          for (auto it = seen; it != chain.end(); ++it) cycle += (cycle.empty() ? "" : ", ") + describe(scene, **it);
          errors.push_back(diagnostic((*seen)->location, "error",
                                      "port references form a cycle, so none of them has a topic: " + cycle));
        } else {
          // The chain joins one settled before: take its result (after an error, any topic will do).
          const std::string topic = scene.components[link->instance].topics.at(link->port);
          for (const auto* r : chain) scene.components[r->instance].topics[r->port] = topic;
        }
        break;
      }
      chain.push_back(link);
      const auto slash = link->target.find('/');
      const std::string other = link->target.substr(0, slash);
      const std::string other_port = link->target.substr(slash + 1);
      const std::size_t target = indexOf(scene, other);
      if (target == scene.components.size()) {
        errors.push_back(
            diagnostic(link->location, "error",
                       "port reference '" + link->target + "': the scene has no component '" + other + "'"));
        break;
      }
      const ComponentInstance& t = scene.components[target];
      if (!t.library->spec().findPort(other_port)) {
        errors.push_back(diagnostic(link->location, "error",
                                    "port reference '" + link->target + "': component '" + other + "' (" + t.type +
                                        ") has no port '" + other_port + "'"));
        break;
      }
      const auto next = referring.find({target, other_port});
      if (next == referring.end()) {
        const std::string topic = t.topics.at(other_port);
        for (const auto* r : chain) scene.components[r->instance].topics[r->port] = topic;
        break;
      }
      link = next->second;
    }
    settled.insert(chain.begin(), chain.end());
  }
}

namespace {

struct Binding {
  const ComponentInstance* instance;
  const PortSpec* port;
  std::string key() const { return instance->name + "." + port->name; }
};

// The topics of the scene with ports of `direction` and `type`, for "did you mean".
std::vector<std::string> topicsWith(const std::map<std::string, std::vector<Binding>>& by_topic,
                                    PortDirection direction, const std::string& type) {
  std::vector<std::string> out;
  for (const auto& [topic, bindings] : by_topic) {
    for (const auto& b : bindings) {
      if (b.port->direction == direction && b.port->type_name == type) {
        out.push_back(topic);
        break;
      }
    }
  }
  return out;
}

std::string didYouMean(const std::string& topic, const std::vector<std::string>& candidates) {
  const std::string guess = closestMatch(topic, candidates);
  return guess.empty() ? "" : "; did you mean '" + guess + "'?";
}

std::string portList(const std::vector<Binding>& bindings) {
  std::string out;
  for (const auto& b : bindings) out += (out.empty() ? "" : ", ") + b.key();
  return out + " (" + bindings.front().port->type_name + ")";
}

bool listed(const std::vector<std::string>& topics, const std::string& topic) {
  return std::find(topics.begin(), topics.end(), topic) != topics.end();
}

// unused_inputs: each topic is read in the scene and written by nobody, in it or beside it
// (external_topics): a stale entry would hide the warning it was meant for once the input is fed.
void checkUnusedInputs(const Scene& scene, const std::map<std::string, std::vector<Binding>>& by_topic,
                       const std::map<std::string, SourceLocation>& unused_inputs, std::vector<std::string>& errors) {
  std::vector<std::string> read;
  for (const auto& [topic, bindings] : by_topic) {
    if (std::any_of(bindings.begin(), bindings.end(),
                    [](const Binding& b) { return b.port->direction == PortDirection::kInput; }))
      read.push_back(topic);
  }
  for (const auto& [topic, where] : unused_inputs) {
    if (!listed(read, topic)) {
      errors.push_back(diagnostic(where, "error",
                                  "unused_inputs: no component in the scene reads " + topic + didYouMean(topic, read)));
      continue;
    }
    std::vector<Binding> writers;
    for (const auto& b : by_topic.at(topic)) {
      if (b.port->direction == PortDirection::kOutput) writers.push_back(b);
    }
    if (!writers.empty()) {
      errors.push_back(diagnostic(where, "error",
                                  "unused_inputs: " + topic + " is written by " + portList(writers) +
                                      " in this scene; an input that is fed is not unused"));
    } else if (listed(scene.external_topics, topic)) {
      errors.push_back(diagnostic(
          where, "error",
          "unused_inputs: " + topic + " is in external_topics too; a topic published beside the scene is not unused"));
    }
  }
}

}  // namespace

namespace {

// Every topic written (or read) in the scene by a component other than `self`, with the first port
// writing (reading) it.
std::map<std::string, const PortSpec*> topicsOf(const Scene& scene, const ComponentInstance* self,
                                                PortDirection direction) {
  std::map<std::string, const PortSpec*> topics;
  for (const auto& c : scene.components) {
    if (&c == self) continue;
    for (const auto& port : c.ports) {
      if (port.direction == direction) topics.emplace(c.topics.at(port.name), &port);
    }
  }
  return topics;
}

std::string checkScenePort(const ComponentInstance& c, const PortSpec& port) {
  if (port.name.empty() || port.name.front() != '/') return "asked for a port that is not a topic: '" + port.name + "'";
  if (port.type_name.empty()) return "asked for port " + port.name + " without a type";
  if (c.topics.count(port.name)) return "asked for port " + port.name + " twice";
  return "";
}

}  // namespace

// Two rounds, so that what one component decides is seen by another whatever their order in the
// file (a recorder of every topic records what a player publishes): the first round finds the
// outputs, the second decides with them. A resolver must only depend on its parameters and on the
// written topics it is given.
void resolveScenePorts(Scene& scene, std::vector<std::string>& errors) {
  for (int round = 0; round < 2; ++round) {
    for (auto& c : scene.components) {
      const ScenePortResolver& resolve = c.library->spec().scenePortResolver();
      if (!resolve) continue;
      // A parameter with an error has no value, and that error is reported already.
      const auto& declared = c.library->spec().parameters();
      if (!std::all_of(declared.begin(), declared.end(), [&](const auto& p) { return c.params.count(p.name); }))
        continue;
      std::vector<PortSpec> decided;
      try {
        decided = resolve(
            {c.params, topicsOf(scene, &c, PortDirection::kOutput), topicsOf(scene, &c, PortDirection::kInput)});
      } catch (const std::exception& e) {
        if (round == 1) {
          errors.push_back(diagnostic(c.location, "error", "component '" + c.name + "' (" + c.type + "): " + e.what()));
        }
        continue;
      }
      // The second round replaces what the first decided.
      c.ports.resize(c.library->spec().ports().size());
      for (auto it = c.topics.begin(); it != c.topics.end();) {
        it = c.library->spec().findPort(it->first) ? std::next(it) : c.topics.erase(it);
      }
      for (auto& port : decided) {
        port.default_topic = port.name;
        port.serialized = true;
        const std::string problem = checkScenePort(c, port);
        if (!problem.empty()) {
          if (round == 1)
            errors.push_back(diagnostic(c.location, "error", "component '" + c.name + "' (" + c.type + ") " + problem));
          continue;
        }
        c.topics[port.name] = port.name;
        c.ports.push_back(std::move(port));
      }
    }
  }
}

// Two writers on one topic: an error where one of their ports must be the topic's only writer
// (PortSpec::sole_writer), a warning otherwise (their samples interleave).
template <class WhereSet>
void checkWriterCount(Scene& scene, const std::string& topic, const std::vector<Binding>& writers,
                      const WhereSet& whereSet, std::vector<std::string>& errors) {
  if (writers.size() < 2) return;
  const auto sole =
      std::find_if(writers.begin(), writers.end(), [](const Binding& b) { return b.port->sole_writer; });
  const std::string what = std::to_string(writers.size()) + " components write " + topic + ": " + portList(writers);
  if (sole != writers.end()) {
    errors.push_back(diagnostic(whereSet(writers[1]), "error",
                                what + "; " + sole->key() + " must be its only writer (give the others another "
                                       "topic under `topics:`, or remove them)"));
  } else {
    scene.warnings.push_back(
        diagnostic(whereSet(writers[1]), "warning", what + " (their samples interleave on the topic)"));
  }
}

// An input whose topic no component of the scene writes is an error only when the scene itself
// remapped that port (an explicit `topics:` entry): there the topic was typed by hand, and a typo
// such as /lo/odometri would leave the reader waiting forever. With the port's own default topic it
// is a warning: some inputs are optional in some scenes (lo's imu, initial_pose), and a process
// group started with `run-process` may be fed from another host. Neither for a topic the scene
// declares fed from outside (external_topics) or left unfed on purpose (unused_inputs). An output
// nobody reads is a warning unless its port or the scene (outputs_for_tools) says it is for
// viewers and tools: many outputs exist for viewers and recorders (/lo/local_map, /world/points).
// One line per topic, so that a scene with many silent ports does not drown the user.
void checkConnections(Scene& scene, const std::map<std::string, SourceLocation>& remapped,
                      const std::map<std::string, SourceLocation>& unused_inputs, std::vector<std::string>& errors) {
  std::map<std::string, std::vector<Binding>> by_topic;
  for (const auto& c : scene.components) {
    for (const auto& port : c.ports) by_topic[c.topics.at(port.name)].push_back({&c, &port});
  }
  auto whereSet = [&](const Binding& b) {
    const auto it = remapped.find(b.key());
    return it != remapped.end() ? it->second : b.instance->location;
  };
  for (const auto& [topic, bindings] : by_topic) {
    const Binding& first = bindings.front();
    std::vector<Binding> readers, writers;
    for (const auto& b : bindings) {
      (b.port->direction == PortDirection::kInput ? readers : writers).push_back(b);
      if (b.port->type_name == first.port->type_name) continue;
      errors.push_back(diagnostic(whereSet(b), "error",
                                  "topic " + topic + " connects ports of different types: " + first.key() + " (" +
                                      first.port->type_name + ") and " + b.key() + " (" + b.port->type_name + ")"));
    }
    checkWriterCount(scene, topic, writers, whereSet, errors);
    const bool fed_or_unused = listed(scene.external_topics, topic) || unused_inputs.count(topic);
    if (writers.empty() && !fed_or_unused) {
      const auto typed =
          std::find_if(readers.begin(), readers.end(), [&](const Binding& b) { return remapped.count(b.key()); });
      const std::string suggestion =
          didYouMean(topic, topicsWith(by_topic, PortDirection::kOutput, readers.front().port->type_name));
      if (typed != readers.end()) {
        errors.push_back(
            diagnostic(whereSet(*typed), "error",
                       "no component in the scene writes " + topic + ", read by " + portList(readers) + suggestion));
      } else {
        scene.warnings.push_back(diagnostic(whereSet(readers.front()), "warning",
                                            "no component in the scene writes " + topic + ", read by " +
                                                portList(readers) + suggestion +
                                                " (fine if another host or program publishes it)"));
      }
    }
    const bool for_viewers =
        std::all_of(writers.begin(), writers.end(), [](const Binding& b) { return b.port->for_viewers; }) ||
        listed(scene.outputs_for_tools, topic);
    if (readers.empty() && !for_viewers) {
      scene.warnings.push_back(diagnostic(
          whereSet(writers.front()), "warning",
          "nobody in the scene reads " + topic + ", written by " + portList(writers) +
              didYouMean(topic, topicsWith(by_topic, PortDirection::kInput, writers.front().port->type_name))));
    }
  }
  checkUnusedInputs(scene, by_topic, unused_inputs, errors);
}

}  // namespace uampc
