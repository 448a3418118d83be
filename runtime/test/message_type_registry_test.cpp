// The registry of message types by ROS name. This file includes no message package except
// std_msgs (for the duplicate registration below): the shipped types it finds were registered by
// the runtime library, not by this test.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "uampc/msgs/std_msgs.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc {
namespace {

TEST(MessageTypeRegistry, FindsShippedTypesByRosNameWithRos2DdsNames) {
  struct Expected {
    const char* ros_name;
    const char* dds_name;
  };
  for (const Expected& e : {Expected{"sensor_msgs/msg/PointCloud2", "sensor_msgs::msg::dds_::PointCloud2_"},
                            Expected{"nav_msgs/msg/Odometry", "nav_msgs::msg::dds_::Odometry_"},
                            Expected{"rosgraph_msgs/msg/Clock", "rosgraph_msgs::msg::dds_::Clock_"},
                            Expected{"uampc/msg/StepAck", "uampc::msg::dds_::StepAck_"},
                            Expected{"geometry_msgs/msg/PoseStamped", "geometry_msgs::msg::dds_::PoseStamped_"}}) {
    const MessageTypeInfo* info = findMessageType(e.ros_name);
    ASSERT_NE(info, nullptr) << e.ros_name;
    EXPECT_EQ(info->ros_name, e.ros_name);
    EXPECT_EQ(info->dds_type_name, e.dds_name);
    // The factory makes the type support of that very type.
    std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type_support(info->make_type_support());
    ASSERT_NE(type_support, nullptr);
    EXPECT_STREQ(type_support->getName(), e.dds_name);
  }
}

TEST(MessageTypeRegistry, UnknownNamesAreNotFound) {
  EXPECT_EQ(findMessageType("sensor_msgs/msg/NoSuchType"), nullptr);
  EXPECT_EQ(findMessageType("sensor_msgs::msg::dds_::PointCloud2_"), nullptr);  // a DDS name is not a ROS name
  EXPECT_EQ(findMessageType(""), nullptr);
}

TEST(MessageTypeRegistry, ListsEveryRegisteredNameSortedAndOnce) {
  const std::vector<std::string> names = messageTypeNames();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  for (const char* name : {"sensor_msgs/msg/JointState", "uampc/msg/MotorCommand", "std_msgs/msg/Float64"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
  for (const std::string& name : names) EXPECT_NE(findMessageType(name), nullptr) << name;
}

TEST(MessageTypeRegistry, ATypeRegisteredTwiceStaysFoundAfterOneRegistrationEnds) {
  // std_msgs/Float64 is registered by the runtime and by this test's include of std_msgs.hpp;
  // one more registration coming and going (a library loaded and unloaded) changes nothing.
  const MessageTypeInfo* before = findMessageType("std_msgs/msg/Float64");
  ASSERT_NE(before, nullptr);
  {
    detail::MessageTypeRegistration<std_msgs::msg::Float64> another;
    EXPECT_EQ(findMessageType("std_msgs/msg/Float64"), before);
  }
  EXPECT_EQ(findMessageType("std_msgs/msg/Float64"), before);
  const std::vector<std::string> names = messageTypeNames();
  EXPECT_EQ(std::count(names.begin(), names.end(), "std_msgs/msg/Float64"), 1);
}

}  // namespace
}  // namespace uampc
