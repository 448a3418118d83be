#include "scene_document.hpp"

#include <algorithm>
#include <filesystem>

#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/yaml_errors.hpp"
#include "yaml_walk.hpp"

namespace fs = std::filesystem;

namespace uampc {

namespace {

constexpr std::size_t kMaxExtendsDepth = 64;

std::string position(const std::string& file, const YAML::Mark& mark) {
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

YAML::Node parse(const std::string& file) {
  try {
    YAML::Node document = YAML::LoadFile(file);
    if (auto errors = yamlStructureErrors(document, file); !errors.empty()) throw SceneError(std::move(errors));
    return document;
  } catch (const YAML::ParserException& e) {
    throw SceneError({position(file, e.mark) + ": error: YAML syntax: " + e.msg});
  } catch (const YAML::Exception& e) {
    throw SceneError({file + ": error: " + e.what()});
  }
}

// The value of `key` in map `node` with its key node, or undefined nodes.
std::pair<YAML::Node, YAML::Node> entry(const YAML::Node& map, const std::string& key) {
  for (const auto& kv : map) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) return {kv.first, kv.second};
  }
  return {YAML::Node(YAML::NodeType::Undefined), YAML::Node(YAML::NodeType::Undefined)};
}

// What identifies a node as YAML::Node::is does, which yaml-cpp 0.7 does not expose: the address
// of the data behind it. Scalar() returns a reference into that data for every kind of node (a
// map's or sequence's is empty but its own); nodes that share data (assigned copies) are one node
// for this purpose, which is right for where it was written.
const void* nodeIdentity(const YAML::Node& node) { return &node.Scalar(); }

}  // namespace

YAML::Node deepMerge(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return over;
  // force_insert keeps the original key and value nodes (and so their file positions); a key
  // written twice in one file stays twice, so that the validator still reports it.
  std::vector<YAML::Node> over_keys, over_values;
  std::unordered_map<std::string, std::vector<std::size_t>> over_by_key;  // unused entries, first first
  for (const auto& o : over) {
    if (o.first.IsScalar()) over_by_key[o.first.Scalar()].push_back(over_keys.size());
    over_keys.push_back(o.first);
    over_values.push_back(o.second);
  }
  for (auto& [key, indices] : over_by_key) std::reverse(indices.begin(), indices.end());
  std::vector<bool> used(over_keys.size(), false);
  YAML::Node merged(YAML::NodeType::Map);
  for (const auto& kv : base) {
    const auto same = kv.first.IsScalar() ? over_by_key.find(kv.first.Scalar()) : over_by_key.end();
    if (same == over_by_key.end() || same->second.empty()) {
      merged.force_insert(kv.first, kv.second);
      continue;
    }
    const std::size_t i = same->second.back();
    same->second.pop_back();
    merged.force_insert(over_keys[i], deepMerge(kv.second, over_values[i]));
    used[i] = true;
  }
  for (std::size_t i = 0; i < over_keys.size(); ++i) {
    if (!used[i]) merged.force_insert(over_keys[i], over_values[i]);
  }
  return merged;
}

void SceneDocument::remember(const YAML::Node& root, const std::string& file) {
  forEachNodeOnce(root, [&](const YAML::Node& node) { origins_.emplace(nodeIdentity(node), file); });
}

YAML::Node SceneDocument::loadChain(const std::string& file, std::vector<std::string>& chain) {
  YAML::Node node = parse(file);
  remember(node, file);
  chain.push_back(file);
  if (!node.IsMap()) return node;
  const auto [key, value] = entry(node, "extends");
  if (!key.IsDefined()) return node;
  const std::string where = position(file, value.Mark());
  if (!value.IsScalar() || value.Scalar().empty()) {
    throw SceneError({where + ": error: extends must name one scene file, relative to this one"});
  }
  fs::path base_path(value.Scalar());
  if (base_path.is_relative()) base_path = fs::path(file).parent_path() / base_path;
  const std::string base = base_path.lexically_normal().string();
  if (std::find(chain.begin(), chain.end(), base) != chain.end()) {
    std::string cycle;
    for (const auto& f : chain) cycle += f + " -> ";
    throw SceneError({where + ": error: extends cycle: " + cycle + base});
  }
  if (!isRegularFile(base)) throw SceneError({where + ": error: extends: scene file not found: " + base});
  // Each level is a recursion here and in the merge: a bound keeps a long chain an error, not a
  // stack overflow (docs/user/scenes.md, "One scene extending another").
  if (chain.size() >= kMaxExtendsDepth) {
    throw SceneError({where + ": error: extends: more than " + std::to_string(kMaxExtendsDepth) +
                      " scenes in one chain (from " + chain.front() + "); a chain that long is a mistake"});
  }
  YAML::Node own(YAML::NodeType::Map);
  for (const auto& kv : node) {
    if (!kv.first.is(key)) own.force_insert(kv.first, kv.second);
  }
  return deepMerge(loadChain(base, chain), own);
}

SceneDocument SceneDocument::load(const std::string& file) {
  SceneDocument document;
  std::vector<std::string> chain;
  document.root = document.loadChain(file, chain);
  return document;
}

const std::string& SceneDocument::fileOf(const YAML::Node& node, const std::string& fallback) const {
  const auto known = origins_.find(nodeIdentity(node));
  return known == origins_.end() ? fallback : known->second;
}

}  // namespace uampc
