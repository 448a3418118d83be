#include "uampc/runtime/component_library.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "uampc/runtime/file_checks.hpp"

namespace fs = std::filesystem;

namespace uampc {

namespace {
const std::string kPrefix = "libuampc_";
const std::string kSuffix = ".so";

std::vector<std::string> defaultDirectories() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("UAMPC_COMPONENT_PATH")) {
    std::stringstream list(env);
    for (std::string dir; std::getline(list, dir, ':');) {
      if (!dir.empty()) dirs.push_back(dir);
    }
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back((exe.parent_path().parent_path() / "lib" / "uampc" / "components").string());
  return dirs;
}
}  // namespace

std::string componentTypeFromFileName(const std::string& file_name) {
  if (file_name.size() <= kPrefix.size() + kSuffix.size()) return {};
  if (file_name.compare(0, kPrefix.size(), kPrefix) != 0) return {};
  if (file_name.compare(file_name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0) return {};
  return file_name.substr(kPrefix.size(), file_name.size() - kPrefix.size() - kSuffix.size());
}

ComponentLibrary::ComponentLibrary(const std::string& path) : path_(path) {
  handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) throw std::runtime_error(path + ": cannot load component library: " + dlerror());
  using EntryPoint = const ComponentPlugin* (*)();
  auto entry = reinterpret_cast<EntryPoint>(dlsym(handle_, UAMPC_COMPONENT_PLUGIN_SYMBOL));
  if (!entry) {
    dlclose(handle_);
    throw std::runtime_error(path + ": not a uampc component library (no " UAMPC_COMPONENT_PLUGIN_SYMBOL
                             " symbol; did it forget UAMPC_REGISTER_COMPONENT?)");
  }
  plugin_ = entry();
  // abi_version is the first field and never moves, so it can be read whatever the version.
  if (!plugin_ || plugin_->abi_version != kComponentAbiVersion) {
    const unsigned found = plugin_ ? plugin_->abi_version : 0;
    dlclose(handle_);
    throw std::runtime_error(path + ": built for component ABI version " + std::to_string(found) +
                             ", but this uampc runtime has version " + std::to_string(kComponentAbiVersion) +
                             "; rebuild the library against this uampc");
  }
  plugin_->describe(spec_);
}

ComponentLibrary::~ComponentLibrary() {
  // Libraries stay loaded until the process exits: Fast DDS may still hold type supports created
  // by their code, and unloading them first would leave dangling vtables.
}

std::unique_ptr<Component> ComponentLibrary::create(Context& context) const {
  return std::unique_ptr<Component>(plugin_->create(context));
}

ComponentCatalog::ComponentCatalog(std::vector<std::string> directories)
    : directories_(directories.empty() ? defaultDirectories() : std::move(directories)) {}

const ComponentLibrary* ComponentCatalog::find(const std::string& type) {
  if (auto it = loaded_.find(type); it != loaded_.end()) return it->second.get();
  for (const auto& dir : directories_) {
    const fs::path candidate = fs::path(dir) / (kPrefix + type + kSuffix);
    if (!isRegularFile(candidate)) continue;  // a type name too long for a file name is unknown too
    auto library = std::make_unique<ComponentLibrary>(candidate.string());
    if (library->spec().type != type) {
      throw std::runtime_error(candidate.string() + ": file name says type '" + type + "' but it registers '" +
                               library->spec().type + "'");
    }
    return (loaded_[type] = std::move(library)).get();
  }
  return nullptr;
}

std::vector<std::string> ComponentCatalog::typeNames() const {
  std::vector<std::string> names;
  for (const auto& dir : directories_) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string type = componentTypeFromFileName(entry.path().filename().string());
      if (!type.empty() && std::find(names.begin(), names.end(), type) == names.end()) names.push_back(type);
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<const ComponentLibrary*> ComponentCatalog::all(std::vector<std::string>* problems) {
  std::vector<const ComponentLibrary*> out;
  for (const auto& type : typeNames()) {
    try {
      if (const auto* library = find(type)) out.push_back(library);
    } catch (const std::exception& e) {
      if (problems) problems->push_back(e.what());
    }
  }
  return out;
}

}  // namespace uampc
