// The registry of message types by ROS name (see message_type.hpp). Filled during static
// initialization of every library that includes a message package header, so it must work before
// main() and from whichever thread calls dlopen.
#include <algorithm>
#include <map>
#include <mutex>

#include "uampc/runtime/message_type.hpp"

namespace uampc {
namespace {

struct Registry {
  std::mutex mutex;
  // Every registration still loaded, oldest first; the oldest answers.
  std::map<std::string, std::vector<const MessageTypeInfo*>> by_ros_name;
  // The same for IDL file texts, by path.
  std::map<std::string, std::vector<const char*>> idl_by_path;
};

// Withdraws one registration (the others of the same entry stay) and the entry once none is left.
template <typename Map, typename Value>
void removeOne(Map& map, const std::string& key, Value value) {
  auto it = map.find(key);
  if (it == map.end()) return;
  auto& values = it->second;
  auto found = std::find(values.begin(), values.end(), value);
  if (found != values.end()) values.erase(found);
  if (values.empty()) map.erase(it);
}

// Never destroyed: libraries unregister from their static destructors, which may run after the
// runtime's own at exit.
Registry& registry() {
  static Registry* instance = new Registry;
  return *instance;
}

}  // namespace

namespace detail {

void registerMessageType(const MessageTypeInfo* info) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.by_ros_name[info->ros_name].push_back(info);
}

void unregisterMessageType(const MessageTypeInfo* info) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  removeOne(r.by_ros_name, info->ros_name, info);
}

void registerIdlFile(const char* path, const char* text) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.idl_by_path[path].push_back(text);
}

void unregisterIdlFile(const char* path, const char* text) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  removeOne(r.idl_by_path, path, text);
}

}  // namespace detail

const MessageTypeInfo* findMessageType(const std::string& ros_name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto it = r.by_ros_name.find(ros_name);
  return it == r.by_ros_name.end() ? nullptr : it->second.front();
}

const char* findIdlFile(const std::string& path) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto it = r.idl_by_path.find(path);
  return it == r.idl_by_path.end() ? nullptr : it->second.front();
}

std::vector<std::string> messageTypeNames() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& entry : r.by_ros_name) names.push_back(entry.first);
  return names;
}

}  // namespace uampc
