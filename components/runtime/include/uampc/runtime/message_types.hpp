// Every message type a port may carry, with its Fast DDS type support and its ROS 2 name.
// Adding a type: write its IDL in idl/, then add one UAMPC_MESSAGE_TYPE line below.
#pragma once

#include "builtin_interfaces/msg/TimePubSubTypes.h"
#include "geometry_msgs/msg/PoseStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "rosgraph_msgs/msg/ClockPubSubTypes.h"
#include "sensor_msgs/msg/ImagePubSubTypes.h"
#include "sensor_msgs/msg/ImuPubSubTypes.h"
#include "sensor_msgs/msg/JointStatePubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "std_msgs/msg/Float64PubSubTypes.h"
#include "uampc/msg/MetricsPubSubTypes.h"
#include "uampc/msg/MotorCommandPubSubTypes.h"
#include "uampc/msg/StepAckPubSubTypes.h"
#include "uampc/msg/UncertaintyProfilePubSubTypes.h"
#include "uampc/msg/WorldMeshPubSubTypes.h"

namespace uampc {

// MessageType<T>::PubSubType is the fastddsgen type support of T; kRosName its ROS 2 name.
template <typename T>
struct MessageType;

#define UAMPC_MESSAGE_TYPE(package, name)                                 \
  template <>                                                             \
  struct MessageType<package::msg::name> {                                \
    using PubSubType = package::msg::name##PubSubType;                    \
    static constexpr const char* kRosName = #package "/msg/" #name;       \
  };

UAMPC_MESSAGE_TYPE(geometry_msgs, PoseStamped)
UAMPC_MESSAGE_TYPE(nav_msgs, Odometry)
UAMPC_MESSAGE_TYPE(rosgraph_msgs, Clock)
UAMPC_MESSAGE_TYPE(sensor_msgs, Image)
UAMPC_MESSAGE_TYPE(sensor_msgs, Imu)
UAMPC_MESSAGE_TYPE(sensor_msgs, JointState)
UAMPC_MESSAGE_TYPE(sensor_msgs, PointCloud2)
UAMPC_MESSAGE_TYPE(std_msgs, Float64)
UAMPC_MESSAGE_TYPE(uampc, Metrics)
UAMPC_MESSAGE_TYPE(uampc, MotorCommand)
UAMPC_MESSAGE_TYPE(uampc, StepAck)
UAMPC_MESSAGE_TYPE(uampc, UncertaintyProfile)
UAMPC_MESSAGE_TYPE(uampc, WorldMesh)

#undef UAMPC_MESSAGE_TYPE

}  // namespace uampc
