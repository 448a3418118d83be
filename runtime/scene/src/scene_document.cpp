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

}  // namespace

YAML::Node deepMerge(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return over;
  // force_insert keeps the original key and value nodes (and so their file positions); a key
  // written twice in one file stays twice, so that the validator still reports it.
  YAML::Node merged(YAML::NodeType::Map);
  std::vector<bool> used(over.size(), false);
  for (const auto& kv : base) {
    std::size_t i = 0;
    bool replaced = false;
    for (const auto& o : over) {
      if (!used[i] && o.first.IsScalar() && kv.first.IsScalar() && o.first.Scalar() == kv.first.Scalar()) {
        merged.force_insert(o.first, deepMerge(kv.second, o.second));
        used[i] = replaced = true;
        break;
      }
      ++i;
    }
    if (!replaced) merged.force_insert(kv.first, kv.second);
  }
  std::size_t i = 0;
  for (const auto& o : over) {
    if (!used[i++]) merged.force_insert(o.first, o.second);
  }
  return merged;
}

void SceneDocument::remember(const YAML::Node& root, const std::string& file) {
  forEachNodeOnce(root, [&](const YAML::Node& node) { origins_.emplace_back(node, file); });
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
  for (const auto& [known, file] : origins_) {
    if (known.is(node)) return file;
  }
  return fallback;
}

}  // namespace uampc
