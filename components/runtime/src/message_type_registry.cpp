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
};

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
  auto it = r.by_ros_name.find(info->ros_name);
  if (it == r.by_ros_name.end()) return;
  auto& infos = it->second;
  infos.erase(std::remove(infos.begin(), infos.end(), info), infos.end());
  if (infos.empty()) r.by_ros_name.erase(it);
}

}  // namespace detail

const MessageTypeInfo* findMessageType(const std::string& ros_name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto it = r.by_ros_name.find(ros_name);
  return it == r.by_ros_name.end() ? nullptr : it->second.front();
}

std::vector<std::string> messageTypeNames() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& entry : r.by_ros_name) names.push_back(entry.first);
  return names;
}

}  // namespace uampc
