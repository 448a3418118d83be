// The CDR decoder and the YAML printer, on samples serialized by the fastddsgen type supports the
// components publish with (little endian, as Fast DDS sends them) and by Fast CDR in big endian:
// every value set must come back exactly, and bad bytes must give an error, never a crash.
#include <gtest/gtest.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "uampc/msgs/all.hpp"
#include "uampc/runtime/cdr_decoder.hpp"
#include "uampc/runtime/message_definition.hpp"
#include "uampc/runtime/yaml_printer.hpp"

namespace uampc {
namespace {

using Bytes = std::vector<std::uint8_t>;

// What Fast DDS puts on the wire for the message.
template <typename Message>
Bytes serialized(Message message) {
  typename MessageType<Message>::PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&message)());
  EXPECT_TRUE(type.serialize(&message, &payload));
  return Bytes(payload.data, payload.data + payload.length);
}

template <typename Message>
Bytes bigEndian(const Message& message) {
  eprosima::fastcdr::FastBuffer buffer;
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::BIG_ENDIANNESS, eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  message.serialize(cdr);
  return Bytes(buffer.getBuffer(), buffer.getBuffer() + cdr.getSerializedDataLength());
}

MessageStructure structureOf(const std::string& ros_name) {
  std::optional<MessageStructure> structure = findMessageStructure(ros_name);
  EXPECT_TRUE(structure.has_value()) << ros_name;
  return structure ? *structure : MessageStructure{};
}

DecodedValue decode(const std::string& ros_name, const Bytes& bytes) {
  return decodeCdr(structureOf(ros_name), bytes.data(), bytes.size());
}

// The decoder's error for these bytes, or "" when it decodes them.
std::string errorOf(const std::string& ros_name, const Bytes& bytes) {
  try {
    decode(ros_name, bytes);
  } catch (const CdrDecodeError& e) {
    return e.what();
  }
  return "";
}

std::vector<double> reals(const DecodedValue& v) {
  EXPECT_EQ(v.kind, DecodedValue::Kind::kScalars);
  std::vector<double> out;
  for (const Scalar& s : v.scalars) out.push_back(s.real);
  return out;
}

void setStamp(std_msgs::msg::Header& header, std::int32_t sec, std::uint32_t nanosec, const std::string& frame) {
  header.stamp().sec(sec);
  header.stamp().nanosec(nanosec);
  header.frame_id(frame);
}

void expectStamp(const DecodedValue& header, std::int32_t sec, std::uint32_t nanosec, const std::string& frame) {
  EXPECT_EQ(header["stamp"]["sec"].scalar.signed_value, sec);
  EXPECT_EQ(header["stamp"]["nanosec"].scalar.unsigned_value, nanosec);
  EXPECT_EQ(header["frame_id"].text, frame);
}

sensor_msgs::msg::JointState jointState() {
  sensor_msgs::msg::JointState m;
  setStamp(m.header(), -3, 4000000000u, "base_link");
  m.name({"motor", "", "yes"});
  m.position({0.1, -2.5, 1e300});
  // velocity stays empty: an empty sequence of doubles is not aligned, the next length must follow at once
  m.effort({1.0 / 3.0, 1e-5});
  return m;
}

sensor_msgs::msg::PointCloud2 pointCloud(std::size_t data_size) {
  sensor_msgs::msg::PointCloud2 m;
  setStamp(m.header(), 7, 1, "lidar");
  m.height(1);
  m.width(3);
  sensor_msgs::msg::PointField x;
  x.name("x");
  x.offset(0);
  x.datatype(sensor_msgs::msg::PointField_Constants::FLOAT32);
  x.count(1);
  sensor_msgs::msg::PointField ring = x;
  ring.name("ring");
  ring.offset(12);
  ring.datatype(sensor_msgs::msg::PointField_Constants::UINT16);
  m.fields({x, ring});
  m.is_bigendian(false);
  m.point_step(14);
  m.row_step(42);
  std::vector<std::uint8_t> data(data_size);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 7);
  m.data(data);
  m.is_dense(true);
  return m;
}

nav_msgs::msg::Odometry odometry() {
  nav_msgs::msg::Odometry m;
  setStamp(m.header(), 100, 999999999u, "odom");
  m.child_frame_id("base_link");
  m.pose().pose().position().x(1.5);
  m.pose().pose().position().y(-0.25);
  m.pose().pose().position().z(3e-9);
  m.pose().pose().orientation().w(std::sqrt(0.5));
  m.pose().pose().orientation().z(-std::sqrt(0.5));
  for (std::size_t i = 0; i < 36; ++i) m.pose().covariance()[i] = 0.5 * static_cast<double>(i);
  m.twist().twist().linear().x(0.7);
  m.twist().twist().angular().z(-1.25);
  for (std::size_t i = 0; i < 36; ++i) m.twist().covariance()[i] = -static_cast<double>(i);
  return m;
}

TEST(CdrDecoder, Float64) {
  std_msgs::msg::Float64 m;
  m.data(0.1);
  const DecodedValue v = decode("std_msgs/msg/Float64", serialized(m));
  ASSERT_EQ(v.kind, DecodedValue::Kind::kStruct);
  EXPECT_EQ(v["data"].scalar.type, PrimitiveType::kFloat64);
  EXPECT_EQ(v["data"].scalar.real, 0.1);
}

TEST(CdrDecoder, JointStateWithStringsAndAnEmptySequence) {
  const DecodedValue v = decode("sensor_msgs/msg/JointState", serialized(jointState()));
  expectStamp(v["header"], -3, 4000000000u, "base_link");
  ASSERT_EQ(v["name"].elements.size(), 3u);
  EXPECT_EQ(v["name"].elements[0].text, "motor");
  EXPECT_EQ(v["name"].elements[1].text, "");
  EXPECT_EQ(v["name"].elements[2].text, "yes");
  EXPECT_EQ(reals(v["position"]), (std::vector<double>{0.1, -2.5, 1e300}));
  EXPECT_TRUE(reals(v["velocity"]).empty());
  EXPECT_EQ(reals(v["effort"]), (std::vector<double>{1.0 / 3.0, 1e-5}));
}

TEST(CdrDecoder, PointCloud2WithItsFieldsAndData) {
  const DecodedValue v = decode("sensor_msgs/msg/PointCloud2", serialized(pointCloud(42)));
  expectStamp(v["header"], 7, 1, "lidar");
  EXPECT_EQ(v["height"].scalar.unsigned_value, 1u);
  EXPECT_EQ(v["width"].scalar.unsigned_value, 3u);
  ASSERT_EQ(v["fields"].elements.size(), 2u);
  const DecodedValue& ring = v["fields"].elements[1];
  EXPECT_EQ(ring["name"].text, "ring");
  EXPECT_EQ(ring["offset"].scalar.unsigned_value, 12u);
  EXPECT_EQ(ring["datatype"].scalar.unsigned_value, 4u);
  EXPECT_EQ(ring["count"].scalar.unsigned_value, 1u);
  EXPECT_EQ(v["is_bigendian"].scalar.boolean, false);
  EXPECT_EQ(v["point_step"].scalar.unsigned_value, 14u);
  EXPECT_EQ(v["row_step"].scalar.unsigned_value, 42u);
  ASSERT_EQ(v["data"].scalars.size(), 42u);
  for (std::size_t i = 0; i < 42; ++i) EXPECT_EQ(v["data"].scalars[i].unsigned_value, (i * 7) % 256) << i;
  EXPECT_EQ(v["is_dense"].scalar.boolean, true);
}

void expectOdometry(const DecodedValue& v) {
  expectStamp(v["header"], 100, 999999999u, "odom");
  EXPECT_EQ(v["child_frame_id"].text, "base_link");
  const DecodedValue& pose = v["pose"]["pose"];
  EXPECT_EQ(pose["position"]["x"].scalar.real, 1.5);
  EXPECT_EQ(pose["position"]["y"].scalar.real, -0.25);
  EXPECT_EQ(pose["position"]["z"].scalar.real, 3e-9);
  EXPECT_EQ(pose["orientation"]["x"].scalar.real, 0.0);
  EXPECT_EQ(pose["orientation"]["z"].scalar.real, -std::sqrt(0.5));
  EXPECT_EQ(pose["orientation"]["w"].scalar.real, std::sqrt(0.5));
  const std::vector<double> pose_covariance = reals(v["pose"]["covariance"]);
  const std::vector<double> twist_covariance = reals(v["twist"]["covariance"]);
  ASSERT_EQ(pose_covariance.size(), 36u);
  ASSERT_EQ(twist_covariance.size(), 36u);
  for (std::size_t i = 0; i < 36; ++i) {
    EXPECT_EQ(pose_covariance[i], 0.5 * static_cast<double>(i));
    EXPECT_EQ(twist_covariance[i], -static_cast<double>(i));
  }
  EXPECT_EQ(v["twist"]["twist"]["linear"]["x"].scalar.real, 0.7);
  EXPECT_EQ(v["twist"]["twist"]["angular"]["z"].scalar.real, -1.25);
}

TEST(CdrDecoder, OdometryInBothByteOrders) {
  const Bytes little = serialized(odometry());
  const Bytes big = bigEndian(odometry());
  ASSERT_EQ(little[1], 1);  // CDR_LE
  ASSERT_EQ(big[1], 0);     // CDR_BE
  expectOdometry(decode("nav_msgs/msg/Odometry", little));
  expectOdometry(decode("nav_msgs/msg/Odometry", big));
}

TEST(CdrDecoder, StepAckWithASequenceOfStructsAndUint64) {
  uampc::msg::StepAck m;
  m.process("sim");
  m.step(-1);
  m.stamp().sec(5);
  uampc::msg::TopicCount a;
  a.topic("/a");
  a.count(std::uint64_t{1} << 40);
  uampc::msg::TopicCount b;
  b.topic("/motor/state");
  b.count(0);
  m.written({a, b});
  m.failed(true);
  m.message("");
  for (const Bytes& bytes : {serialized(m), bigEndian(m)}) {
    const DecodedValue v = decode("uampc/msg/StepAck", bytes);
    EXPECT_EQ(v["process"].text, "sim");
    EXPECT_EQ(v["step"].scalar.signed_value, -1);
    EXPECT_EQ(v["stamp"]["sec"].scalar.signed_value, 5);
    ASSERT_EQ(v["written"].elements.size(), 2u);
    EXPECT_EQ(v["written"].elements[0]["topic"].text, "/a");
    EXPECT_EQ(v["written"].elements[0]["count"].scalar.unsigned_value, std::uint64_t{1} << 40);
    EXPECT_EQ(v["written"].elements[1]["topic"].text, "/motor/state");
    EXPECT_EQ(v["written"].elements[1]["count"].scalar.unsigned_value, 0u);
    EXPECT_EQ(v["failed"].scalar.boolean, true);
    EXPECT_EQ(v["message"].text, "");
  }
}

TEST(CdrDecoder, Float32SequencesOfAWorldMesh) {
  uampc::msg::WorldMesh m;
  m.vertices({0.1f, -1.5f, 3.0e38f});
  m.triangles({0, 1, 4294967295u});
  m.point_radius(0.05f);
  const DecodedValue v = decode("uampc/msg/WorldMesh", serialized(m));
  ASSERT_EQ(v["vertices"].scalars.size(), 3u);
  EXPECT_EQ(v["vertices"].element_type, PrimitiveType::kFloat32);
  EXPECT_EQ(static_cast<float>(v["vertices"].scalars[0].real), 0.1f);
  EXPECT_EQ(v["vertices"].scalars[0].real, static_cast<double>(0.1f));
  EXPECT_EQ(v["vertices"].scalars[2].real, static_cast<double>(3.0e38f));
  EXPECT_EQ(v["triangles"].scalars[2].unsigned_value, 4294967295u);
  EXPECT_EQ(v["point_radius"].scalar.real, static_cast<double>(0.05f));
}

// ---- bad bytes ----

TEST(CdrDecoder, EveryTruncationIsAnError) {
  const Bytes whole = serialized(jointState());
  for (std::size_t size = 0; size < whole.size(); ++size) {
    const std::string error = errorOf("sensor_msgs/msg/JointState", Bytes(whole.begin(), whole.begin() + size));
    EXPECT_EQ(error.rfind("truncated sample: ", 0), 0u) << size << " bytes: " << error;
  }
  EXPECT_EQ(errorOf("sensor_msgs/msg/JointState", Bytes(whole.begin(), whole.begin() + 20)),
            "truncated sample: header.frame_id needs 10 bytes at offset 16, 4 left");
}

TEST(CdrDecoder, ALengthLongerThanWhatIsLeftIsAnError) {
  Bytes bytes = serialized(jointState());
  // header.frame_id's length is at offset 12 (after the header and the stamp's two 4-byte fields).
  ASSERT_EQ(bytes[12], 10);  // "base_link" and its NUL
  bytes[12] = 200;
  EXPECT_EQ(errorOf("sensor_msgs/msg/JointState", bytes).rfind("truncated sample: header.frame_id needs 200 bytes", 0),
            0u);
}

TEST(CdrDecoder, AHugeSequenceLengthIsAnErrorNotAnAllocation) {
  const Bytes whole = serialized(pointCloud(8));
  // data's length is the 4 bytes before the 8 data bytes and is_dense.
  const std::size_t length_at = whole.size() - 8 - 1 - 4;
  ASSERT_EQ(whole[length_at], 8);
  for (std::uint32_t huge : {0x7fffffffu, 0xfffffff0u}) {
    Bytes bytes = whole;
    for (int i = 0; i < 4; ++i) bytes[length_at + i] = static_cast<std::uint8_t>(huge >> (8 * i));
    EXPECT_EQ(errorOf("sensor_msgs/msg/PointCloud2", bytes),
              "truncated sample: data has " + std::to_string(huge) + " elements, more than the 9 bytes left can hold");
  }
  // A sequence of structs (PointField: at least 13 bytes each) is checked the same way.
  Bytes bytes = whole;
  // After the CDR header, the stamp, frame_id ("lidar" and its NUL after its length, 2 bytes of
  // padding), height and width.
  const std::size_t fields_length_at = 4 + 8 + 4 + 6 + 2 + 4 + 4;
  ASSERT_EQ(bytes[fields_length_at], 2);
  bytes[fields_length_at] = 0xff;
  bytes[fields_length_at + 3] = 0x0f;
  EXPECT_EQ(errorOf("sensor_msgs/msg/PointCloud2", bytes).rfind("truncated sample: fields has 251658495 elements", 0),
            0u);
}

TEST(CdrDecoder, OtherBadBytesAreNamed) {
  std_msgs::msg::Float64 f;
  f.data(1.0);
  Bytes bytes = serialized(f);
  EXPECT_EQ(errorOf("std_msgs/msg/Float64", Bytes(bytes.begin(), bytes.begin() + 3)),
            "truncated sample: 3 bytes, less than the 4-byte CDR header");
  Bytes padded = bytes;
  padded.insert(padded.end(), 3, 0);  // other vendors pad to 4 bytes
  EXPECT_EQ(errorOf("std_msgs/msg/Float64", padded), "");
  padded.push_back(0);
  EXPECT_EQ(errorOf("std_msgs/msg/Float64", padded),
            "4 bytes left after the last field (offset 12 of 16): the sample is not a std_msgs::msg::Float64");
  for (std::uint8_t representation : {2, 3, 7, 11, 0x40}) {
    Bytes other = bytes;
    other[1] = representation;
    EXPECT_FALSE(errorOf("std_msgs/msg/Float64", other).empty()) << int{representation};
  }
  bytes[1] = 7;
  EXPECT_EQ(errorOf("std_msgs/msg/Float64", bytes),
            "XCDR2 encapsulation 0x0007 is not supported: only plain CDR (XCDR1, as Fast DDS 2.9 writes)");

  Bytes cloud = serialized(pointCloud(0));
  cloud.back() = 2;  // is_dense
  EXPECT_EQ(errorOf("sensor_msgs/msg/PointCloud2", cloud), "is_dense: a bool is 2, neither 0 nor 1");
}

// ---- YAML ----

TEST(YamlPrinter, NestedStructsIndentedAndSequencesOfPrimitivesInFlowStyle) {
  EXPECT_EQ(toYaml(decode("sensor_msgs/msg/JointState", serialized(jointState()))),
            "header:\n"
            "  stamp:\n"
            "    sec: -3\n"
            "    nanosec: 4000000000\n"
            "  frame_id: base_link\n"
            "name: [motor, '', 'yes']\n"
            "position: [0.1, -2.5, 1.0e+300]\n"
            "velocity: []\n"
            "effort: [0.3333333333333333, 1.0e-05]\n");
}

TEST(YamlPrinter, FloatsAreWrittenAsPythonsReprWrites) {
  // Positional from 1e-4 to below 1e16, else scientific; always with a '.' (PyYAML).
  const std::vector<std::pair<double, std::string>> cases = {{100.0, "100.0"},  {1500.0, "1500.0"}, {0.0001, "0.0001"},
                                                             {1e-5, "1.0e-05"}, {1e16, "1.0e+16"},  {-2.5, "-2.5"}};
  for (const auto& [value, text] : cases) {
    std_msgs::msg::Float64 m;
    m.data(value);
    EXPECT_EQ(toYaml(decode("std_msgs/msg/Float64", serialized(m))), "data: " + text + "\n") << value;
  }
}

TEST(YamlPrinter, SequencesOfStructsAsItemsAndLongByteArraysElided) {
  const DecodedValue v = decode("sensor_msgs/msg/PointCloud2", serialized(pointCloud(kLongestBytesShown + 1)));
  const std::string expected_start =
      "header:\n"
      "  stamp:\n"
      "    sec: 7\n"
      "    nanosec: 1\n"
      "  frame_id: lidar\n"
      "height: 1\n"
      "width: 3\n"
      "fields:\n"
      "- name: x\n"
      "  offset: 0\n"
      "  datatype: 7\n"
      "  count: 1\n"
      "- name: ring\n"
      "  offset: 12\n"
      "  datatype: 4\n"
      "  count: 1\n"
      "is_bigendian: false\n"
      "point_step: 14\n"
      "row_step: 42\n";
  EXPECT_EQ(toYaml(v), expected_start + "data: <33 bytes>\nis_dense: true\n");
  std::string all_bytes = "data: [";
  for (std::size_t i = 0; i <= kLongestBytesShown; ++i) all_bytes += (i ? ", " : "") + std::to_string((i * 7) % 256);
  EXPECT_EQ(toYaml(v, YamlOptions{true}), expected_start + all_bytes + "]\nis_dense: true\n");
  // Up to kLongestBytesShown bytes are shown anyway.
  const DecodedValue short_data = decode("sensor_msgs/msg/PointCloud2", serialized(pointCloud(3)));
  EXPECT_NE(toYaml(short_data).find("\ndata: [0, 7, 14]\n"), std::string::npos);
}

TEST(YamlPrinter, StructsInSequenceItemsIndentUnderTheirItem) {
  uampc::msg::Metrics m;
  setStamp(m.header(), 1, 2, "map");
  uampc::msg::MetricValue value;
  value.name("ate");
  value.value(0.25);
  value.unit("m");
  m.values({value});
  m.source("evaluator");
  EXPECT_EQ(toYaml(decode("uampc/msg/Metrics", serialized(m))),
            "header:\n"
            "  stamp:\n"
            "    sec: 1\n"
            "    nanosec: 2\n"
            "  frame_id: map\n"
            "source: evaluator\n"
            "values:\n"
            "- name: ate\n"
            "  value: 0.25\n"
            "  unit: m\n");
}

TEST(YamlPrinter, FloatsReadBackExactlyWithTheFewestDigits) {
  Scalar s;
  s.type = PrimitiveType::kFloat64;
  for (double value : {0.1, 1.0 / 3.0, -2.5, 1e-300, 5e-324, 123456789.125, 1e16, 1e22, -0.0, 0.0,
                       std::numeric_limits<double>::max()}) {
    s.real = value;
    const std::string text = yamlScalar(s);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), value) << text;
    EXPECT_NE(text.find('.'), std::string::npos) << text;
  }
  s.real = 0.1;
  EXPECT_EQ(yamlScalar(s), "0.1");
  s.real = 1.0;
  EXPECT_EQ(yamlScalar(s), "1.0");
  s.real = -0.0;
  EXPECT_EQ(yamlScalar(s), "-0.0");
  s.real = std::nan("");
  EXPECT_EQ(yamlScalar(s), ".nan");
  s.real = -HUGE_VAL;
  EXPECT_EQ(yamlScalar(s), "-.inf");
  s.type = PrimitiveType::kFloat32;
  s.real = 0.1f;  // 0.100000001490116... as a double
  EXPECT_EQ(yamlScalar(s), "0.1");
  s.real = 16777217.0f;
  EXPECT_EQ(std::strtof(yamlScalar(s).c_str(), nullptr), 16777217.0f);
}

TEST(YamlPrinter, StringsAreQuotedWhereYamlWouldReadThemOtherwise) {
  EXPECT_EQ(yamlString("base_link"), "base_link");
  EXPECT_EQ(yamlString("/lidar/points"), "/lidar/points");
  EXPECT_EQ(yamlString("campus seed 1"), "campus seed 1");
  EXPECT_EQ(yamlString(""), "''");
  EXPECT_EQ(yamlString("true"), "'true'");
  EXPECT_EQ(yamlString("No"), "'No'");
  EXPECT_EQ(yamlString("null"), "'null'");
  EXPECT_EQ(yamlString("12"), "'12'");
  EXPECT_EQ(yamlString("1e3"), "'1e3'");
  EXPECT_EQ(yamlString(" padded"), "' padded'");
  EXPECT_EQ(yamlString("a: b"), "'a: b'");
  EXPECT_EQ(yamlString("x #y"), "'x #y'");
  EXPECT_EQ(yamlString("[1]"), "'[1]'");
  EXPECT_EQ(yamlString("a,b"), "'a,b'");
  EXPECT_EQ(yamlString("- item"), "'- item'");
  EXPECT_EQ(yamlString("it's"), "it's");
  EXPECT_EQ(yamlString("'quoted'"), "'''quoted'''");
  EXPECT_EQ(yamlString("two\nlines\t\x01"), "\"two\\nlines\\t\\x01\"");
}

}  // namespace
}  // namespace uampc
