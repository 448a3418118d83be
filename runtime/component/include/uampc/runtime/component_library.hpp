// Finding and loading component libraries (dlopen, one exported C symbol, ABI check).
//
// A component type "motor_bridge" lives in libuampc_motor_bridge.so, found in the directories of
// UAMPC_COMPONENT_PATH (colon-separated, searched first) and then <uampc binary>/../lib/uampc/components.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "uampc/runtime/component.hpp"

namespace uampc {

class ComponentLibrary {
 public:
  // Loads the library and checks its ABI version; throws std::runtime_error naming the file.
  explicit ComponentLibrary(const std::string& path);
  ~ComponentLibrary();
  ComponentLibrary(const ComponentLibrary&) = delete;
  ComponentLibrary& operator=(const ComponentLibrary&) = delete;

  const std::string& path() const { return path_; }
  const ComponentSpec& spec() const { return spec_; }
  std::unique_ptr<Component> create(Context& context) const;

 private:
  std::string path_;
  void* handle_ = nullptr;
  const ComponentPlugin* plugin_ = nullptr;
  ComponentSpec spec_;
};

class ComponentCatalog {
 public:
  // Search directories in order; empty: the default (environment, then next to the binary).
  explicit ComponentCatalog(std::vector<std::string> directories = {});

  // The library of a type, loaded on first use; nullptr if no directory has it.
  // Throws if the file exists but cannot be loaded (wrong ABI, missing symbol, ...).
  const ComponentLibrary* find(const std::string& type);
  // Every library in the search directories, loaded; failures are returned in `problems`.
  std::vector<const ComponentLibrary*> all(std::vector<std::string>* problems = nullptr);
  // Type names found on disk, without loading them.
  std::vector<std::string> typeNames() const;
  const std::vector<std::string>& directories() const { return directories_; }

 private:
  std::vector<std::string> directories_;
  std::map<std::string, std::unique_ptr<ComponentLibrary>> loaded_;  // by type
};

// "libuampc_motor_bridge.so" -> "motor_bridge"; empty if the name does not follow the convention.
std::string componentTypeFromFileName(const std::string& file_name);

}  // namespace uampc
