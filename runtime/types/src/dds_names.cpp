#include "uampc/runtime/dds_names.hpp"

#include <cstdlib>
#include <stdexcept>

namespace uampc {

namespace {
constexpr char kTopicPrefix[] = "rt";  // ROS topics; services and actions use other prefixes
constexpr char kTypeInfix[] = "::dds_::";
}  // namespace

std::string ddsTopicName(const std::string& ros_topic) { return kTopicPrefix + ros_topic; }

std::string rosTopicName(const std::string& dds_topic) {
  const std::string prefix = std::string(kTopicPrefix) + "/";
  if (dds_topic.compare(0, prefix.size(), prefix) != 0 || dds_topic.size() == prefix.size()) return "";
  return dds_topic.substr(prefix.size() - 1);
}

std::string ddsTypeName(const std::string& ros_type) {
  const auto last = ros_type.rfind('/');
  if (last == std::string::npos) return ros_type;
  std::string scope = ros_type.substr(0, last);
  for (std::size_t i; (i = scope.find('/')) != std::string::npos;) scope.replace(i, 1, "::");
  return scope + kTypeInfix + ros_type.substr(last + 1) + "_";
}

std::string rosTypeName(const std::string& dds_type) {
  const auto infix = dds_type.rfind(kTypeInfix);
  if (infix == std::string::npos || dds_type.size() <= infix + sizeof(kTypeInfix) || dds_type.back() != '_') {
    return "";
  }
  std::string scope = dds_type.substr(0, infix);
  for (std::size_t i; (i = scope.find("::")) != std::string::npos;) scope.replace(i, 2, "/");
  const std::size_t name_start = infix + sizeof(kTypeInfix) - 1;
  return scope + "/" + dds_type.substr(name_start, dds_type.size() - name_start - 1);
}

std::optional<int> rosDomainIdFromEnvironment() {
  const char* env = std::getenv("ROS_DOMAIN_ID");
  if (!env || !*env) return std::nullopt;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  if (*end != '\0' || v < 0 || v > kMaxDomainId) {
    throw std::invalid_argument("ROS_DOMAIN_ID is '" + std::string(env) + "', not a domain id between 0 and " +
                                std::to_string(kMaxDomainId));
  }
  return static_cast<int>(v);
}

}  // namespace uampc
