// Message definitions derived from IDL: the structure of a message type, parsed from its IDL file and
// every file that includes (idl_parser.hpp), and its text in rosbag2's "ros2msg" schema encoding, the
// one messageDefinition (message_type.hpp) answers with.
//
// ros2msg: the type's .msg text; then, for each type it uses, depth first and each once, a line of
// 80 '=', a line "MSG: pkg/Type" and that type's .msg text. A type's dependencies follow it sorted by
// name, each followed at once by its own: the order rosbag2 writes (rosbag2_storage_mcap's
// message_definition_cache). The .msg text of a struct is a line per constant ("uint8 INT8=1") and
// per field ("float64[36] covariance", "PointField[] fields", "float64 w 1" with a @default, a field's
// // comment after a '#'); types of the same package by short name, others as pkg/Type.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "uampc/runtime/message_structure.hpp"

namespace uampc {

// The text of an IDL file by its path in the IDL tree ("std_msgs/msg/Header.idl"); nullptr when
// there is no such file.
using IdlFileSource = std::function<const char*(const std::string& path)>;

// The structure of the message type `ros_name` ("sensor_msgs/msg/PointCloud2"): the struct
// sensor_msgs::msg::PointCloud2 of "sensor_msgs/msg/PointCloud2.idl" and every struct it uses, from
// that file and the files it includes. nullopt when `files` has no file for the type. Throws IdlError
// naming file and line for IDL outside the parser's subset, an include `files` lacks, a type no
// file defines or a type that contains itself.
std::optional<MessageStructure> loadMessageStructure(const std::string& ros_name, const IdlFileSource& files);
// The same with the IDL files of the registry (findIdlFile): the types of every loaded library.
std::optional<MessageStructure> findMessageStructure(const std::string& ros_name);

// The ros2msg text of a message type.
std::string ros2msgDefinition(const MessageStructure& structure);

// How .msg files name a struct: "sensor_msgs::msg::PointField" -> "sensor_msgs/PointField".
std::string msgTypeName(const std::string& qualified_struct_name);

}  // namespace uampc
