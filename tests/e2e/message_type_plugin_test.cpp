// A component library with an IDL package of its own (tests/idl/uampc_test_msgs) registers that
// package's types when it is loaded: the runtime finds uampc_test_msgs/msg/Ping by ROS name,
// though neither it nor this test is compiled against the type.
#include <gtest/gtest.h>

#include <dlfcn.h>

#include <algorithm>
#include <memory>

#include "command_runner.hpp"
#include "uampc/runtime/component_library.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc::test {
namespace {

constexpr const char* kPing = "uampc_test_msgs/msg/Ping";

std::string pingPublisherPath() { return binaryPath("tests/components/libuampc_ping_publisher.so"); }

TEST(MessageTypePlugin, ALibraryRegistersItsOwnTypesWhenLoadedAndWithdrawsThemWhenUnloaded) {
  ASSERT_EQ(findMessageType(kPing), nullptr) << "no library with Ping is loaded yet";
  // Loaded and unloaded as the loader does with a library it refuses (wrong ABI): once it is
  // gone, no pointer into it may remain in the registry.
  void* handle = dlopen(pingPublisherPath().c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << dlerror();
  EXPECT_NE(findMessageType(kPing), nullptr);
  ASSERT_EQ(dlclose(handle), 0);
  EXPECT_EQ(findMessageType(kPing), nullptr);

  // Loaded by the component loader, as a scene does.
  ComponentLibrary library(pingPublisherPath());
  const MessageTypeInfo* info = findMessageType(kPing);
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->ros_name, kPing);
  EXPECT_EQ(info->dds_type_name, "uampc_test_msgs::msg::dds_::Ping_");
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type_support(info->make_type_support());
  EXPECT_STREQ(type_support->getName(), "uampc_test_msgs::msg::dds_::Ping_");
  const std::vector<std::string> names = messageTypeNames();
  EXPECT_NE(std::find(names.begin(), names.end(), kPing), names.end());
  // The port the component declares carries the name the registry answers to.
  ASSERT_EQ(library.spec().ports().size(), 1u);
  EXPECT_EQ(library.spec().ports()[0].type_name, kPing);
  // The shipped types are still the runtime's own.
  EXPECT_NE(findMessageType("sensor_msgs/msg/PointCloud2"), nullptr);
}

}  // namespace
}  // namespace uampc::test
