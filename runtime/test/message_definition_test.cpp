// Message definitions derived from IDL. The expected texts of the shipped types were written from
// ROS 2 Humble's .msg files (ros2/common_interfaces 4.2.x): their field and constant lines, in their
// order, joined the way rosbag2 joins a type and its dependencies. Two differences from the bytes
// rosbag2 writes are by construction: ROS's .msg comments, blank lines and column alignment are not
// in our IDL, so they are not in the text either (a definition's meaning does not depend on them);
// and Quaternion's defaults ("float64 w 1") are missing because idl/geometry_msgs/msg/Quaternion.idl
// has no @default annotations (see the test of @default below for what an annotated IDL gives).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "uampc/runtime/idl_parser.hpp"
#include "uampc/runtime/message_definition.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc {
namespace {

const std::string kSeparator = "\n" + std::string(80, '=') + "\nMSG: ";

const std::string kTime =
    "int32 sec\n"
    "uint32 nanosec\n";

const std::string kHeader =
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n" +
    kSeparator + "builtin_interfaces/Time\n" + kTime;

const std::string kPointField =
    "uint8 INT8=1\n"
    "uint8 UINT8=2\n"
    "uint8 INT16=3\n"
    "uint8 UINT16=4\n"
    "uint8 INT32=5\n"
    "uint8 UINT32=6\n"
    "uint8 FLOAT32=7\n"
    "uint8 FLOAT64=8\n"
    "string name\n"
    "uint32 offset\n"
    "uint8 datatype\n"
    "uint32 count\n";

TEST(MessageDefinition, HeaderIsItsMsgTextThenTime) { EXPECT_EQ(messageDefinition("std_msgs/msg/Header"), kHeader); }

TEST(MessageDefinition, PointCloud2HasPointFieldWithItsConstantsThenHeaderThenTime) {
  const std::string expected =
      "std_msgs/Header header\n"
      "uint32 height\n"
      "uint32 width\n"
      "PointField[] fields\n"
      "bool is_bigendian\n"
      "uint32 point_step\n"
      "uint32 row_step\n"
      "uint8[] data\n"
      "bool is_dense\n" +
      kSeparator + "sensor_msgs/PointField\n" + kPointField + kSeparator + "std_msgs/Header\n" + kHeader;
  EXPECT_EQ(messageDefinition("sensor_msgs/msg/PointCloud2"), expected);
}

TEST(MessageDefinition, OdometryFollowsEachDependencyDepthFirstInNameOrder) {
  const std::string xyz = "float64 x\nfloat64 y\nfloat64 z\n";
  const std::string expected =
      "std_msgs/Header header\n"
      "string child_frame_id\n"
      "geometry_msgs/PoseWithCovariance pose\n"
      "geometry_msgs/TwistWithCovariance twist\n" +
      kSeparator + "geometry_msgs/PoseWithCovariance\n" +
      "Pose pose\n"
      "float64[36] covariance\n" +
      kSeparator + "geometry_msgs/Pose\n" +
      "Point position\n"
      "Quaternion orientation\n" +
      kSeparator + "geometry_msgs/Point\n" + xyz + kSeparator + "geometry_msgs/Quaternion\n" + xyz + "float64 w\n" +
      kSeparator + "geometry_msgs/TwistWithCovariance\n" +
      "Twist twist\n"
      "float64[36] covariance\n" +
      kSeparator + "geometry_msgs/Twist\n" +
      "Vector3 linear\n"
      "Vector3 angular\n" +
      kSeparator + "geometry_msgs/Vector3\n" + xyz + kSeparator + "std_msgs/Header\n" + kHeader;
  EXPECT_EQ(messageDefinition("nav_msgs/msg/Odometry"), expected);
}

TEST(MessageDefinition, OurOwnTypesKeepTheirFieldCommentsAndNestedTypesOfTheirPackage) {
  const std::string definition = messageDefinition("uampc/msg/Metrics");
  EXPECT_EQ(definition.substr(0, definition.find(kSeparator)),
            "std_msgs/Header header\n"
            "string source  # component instance name\n"
            "MetricValue[] values\n");
  EXPECT_NE(definition.find(kSeparator + "uampc/MetricValue\nstring name\nfloat64 value\nstring unit  # SI unit"),
            std::string::npos);
}

TEST(MessageDefinition, EveryRegisteredTypeHasOne) {
  for (const std::string& name : messageTypeNames()) {
    const std::string definition = messageDefinition(name);
    EXPECT_FALSE(definition.empty()) << name;
    EXPECT_EQ(definition.back(), '\n') << name;
  }
}

TEST(MessageDefinition, AnUnknownTypeHasNone) {
  EXPECT_EQ(messageDefinition("sensor_msgs/msg/NoSuchType"), "");
  EXPECT_EQ(messageDefinition("sensor_msgs::msg::dds_::PointCloud2_"), "");
  EXPECT_EQ(messageDefinition(""), "");
}

TEST(MessageDefinition, TheRegistryHoldsTheIdlFilesAsWritten) {
  const char* text = findIdlFile("sensor_msgs/msg/PointField.idl");
  ASSERT_NE(text, nullptr);
  EXPECT_NE(std::string(text).find("const uint8 FLOAT64 = 8;"), std::string::npos);
  EXPECT_EQ(findIdlFile("sensor_msgs/msg/Nothing.idl"), nullptr);
}

// ---- the parser, on IDL files of the tests' own ----

using Files = std::map<std::string, std::string>;

std::optional<MessageStructure> load(const std::string& ros_name, const Files& files) {
  return loadMessageStructure(ros_name, [&files](const std::string& path) -> const char* {
    const auto found = files.find(path);
    return found == files.end() ? nullptr : found->second.c_str();
  });
}

std::string definitionOf(const std::string& ros_name, const Files& files) {
  const std::optional<MessageStructure> structure = load(ros_name, files);
  EXPECT_TRUE(structure.has_value()) << ros_name;
  return structure ? ros2msgDefinition(*structure) : "";
}

// The IdlError's message, or "" when there is none.
std::string errorOf(const std::string& ros_name, const Files& files) {
  try {
    load(ros_name, files);
  } catch (const IdlError& e) {
    return e.what();
  }
  return "";
}

TEST(IdlParser, ReadsEveryPartOfTheSubset) {
  const Files files = {{"p/msg/All.idl", R"idl(// a file comment
#include "q/msg/Other.idl"
#ifndef GUARD
#pragma once
module p {
  module msg {
    typedef double double__9[9];
    module All_Constants {
      const int8 NEGATIVE = -3;
      const uint16 HEX = 0x10;
      const boolean YES = TRUE;
      const double HALF = 0.5;
      const string NAME = "a \"name\"";
    };
    /* a block
       comment */
    @verbatim (language="comment", text="skipped" "\n" "too")
    struct All {
      boolean flag;
      octet raw;
      char letter;
      short s; unsigned short us; long l; unsigned long ul; long long ll; unsigned long long ull;
      int8 i8; uint8 u8; int16 i16; uint16 u16; int32 i32; uint32 u32; int64 i64; uint64 u64;
      float f; double d;
      string text;
      string<10> bounded_text;
      sequence<int32> numbers;  // trailing comment
      sequence<int32, 5> few_numbers;
      sequence<string<4>> short_words;
      double__9 matrix;
      uint8 bytes[16];
      @default (value=1.5)
      double with_default;
      @default (value="hello")
      string greeting;
      @default (value="(1, 2)")
      sequence<int32> list_default;
      double x, y;
      q::msg::Other other;
      Local local;
    };
    struct Local { sequence<q::msg::Other, 2> others; };
  };
};
#endif
)idl"},
                       {"q/msg/Other.idl", "module q { module msg { struct Other { uint8 value; }; }; };"}};
  EXPECT_EQ(definitionOf("p/msg/All", files),
            "int8 NEGATIVE=-3\n"
            "uint16 HEX=16\n"
            "bool YES=true\n"
            "float64 HALF=0.5\n"
            "string NAME=\"a \\\"name\\\"\"\n"
            "bool flag\n"
            "byte raw\n"
            "char letter\n"
            "int16 s\nuint16 us\nint32 l\nuint32 ul\nint64 ll\nuint64 ull\n"
            "int8 i8\nuint8 u8\nint16 i16\nuint16 u16\nint32 i32\nuint32 u32\nint64 i64\nuint64 u64\n"
            "float32 f\nfloat64 d\n"
            "string text\n"
            "string<=10 bounded_text\n"
            "int32[] numbers  # trailing comment\n"
            "int32[<=5] few_numbers\n"
            "string<=4[] short_words\n"
            "float64[9] matrix\n"
            "uint8[16] bytes\n"
            "float64 with_default 1.5\n"
            "string greeting \"hello\"\n"
            "int32[] list_default [1, 2]\n"
            "float64 x\n"
            "float64 y\n"
            "q/Other other\n"
            "Local local\n" +
                kSeparator + "p/Local\n" + "q/Other[<=2] others\n" + kSeparator + "q/Other\n" + "uint8 value\n");
}

TEST(IdlParser, KeepsTheStructureForTheDecoder) {
  const Files files = {{"p/msg/A.idl",
                        "module p { module msg { struct B { double v; };\n"
                        "struct A { sequence<B> bs; uint8 raw[4]; string<3> s; }; }; };"}};
  const std::optional<MessageStructure> structure = load("p/msg/A", files);
  ASSERT_TRUE(structure.has_value());
  EXPECT_EQ(structure->root, "p::msg::A");
  ASSERT_EQ(structure->structs.size(), 2u);
  const StructDefinition& a = structure->rootStruct();
  ASSERT_EQ(a.fields.size(), 3u);
  EXPECT_EQ(a.fields[0].type.kind, FieldType::Kind::kStruct);
  EXPECT_EQ(a.fields[0].type.struct_name, "p::msg::B");
  EXPECT_EQ(a.fields[0].collection, FieldDefinition::Collection::kSequence);
  EXPECT_EQ(a.fields[1].type.primitive, PrimitiveType::kUInt8);
  EXPECT_EQ(a.fields[1].collection, FieldDefinition::Collection::kArray);
  EXPECT_EQ(a.fields[1].size, 4u);
  EXPECT_EQ(a.fields[2].type.kind, FieldType::Kind::kString);
  EXPECT_EQ(a.fields[2].type.string_bound, 3u);
  EXPECT_EQ(a.fields[2].line, 2);
}

TEST(IdlParser, AFileThatIsNotThereIsNoType) {
  EXPECT_FALSE(load("p/msg/A", {}).has_value());
  EXPECT_FALSE(load("not a ros name", {{"not a ros name.idl", ""}}).has_value());
}

TEST(IdlParser, ErrorsNameFileAndLine) {
  struct Case {
    std::string idl;
    std::string error;
  };
  const std::string open = "module p { module msg {\n";
  const std::string close = "}; };\n";
  for (const Case& c : std::vector<Case>{
           {open + "struct A {\n  Missing m;\n};\n" + close, "p/msg/A.idl:3: unknown type 'Missing'"},
           {open + "union A switch (long) { case 1: long x; };\n" + close, "p/msg/A.idl:2: 'union' is not part of"},
           {open + "enum E { X };\n" + close, "p/msg/A.idl:2: 'enum' is not part of"},
           {open + "struct A {\n  wstring w;\n};\n" + close, "p/msg/A.idl:3: wide characters"},
           {open + "struct A {\n  sequence<sequence<int32>> s;\n};\n" + close,
            "p/msg/A.idl:3: a sequence of sequences"},
           {open + "struct A {\n  double m[2][3];\n};\n" + close, "p/msg/A.idl:3: multidimensional arrays"},
           {open + "struct A {\n  double m[0];\n};\n" + close, "p/msg/A.idl:3: expected an array length"},
           {open + "struct A {\n  double d\n};\n" + close, "p/msg/A.idl:4: expected ';', got '}'"},
           {open + "struct A {\n  double d;\n", "p/msg/A.idl:2: struct p::msg::A is not closed"},
           {open + "struct A {\n  @optional double d;\n};\n" + close, "p/msg/A.idl:3: @optional"},
           {open + "struct A { sequence<A> children; };\n" + close, "p/msg/A.idl:2: struct p::msg::A contains itself"},
           {open + "module B_Constants { const uint8 X = 1; };\nstruct A { double d; };\n" + close,
            "p/msg/A.idl:2: constants for p::msg::B"},
           {open + "const uint8 X = 1;\n" + close, "p/msg/A.idl:2: a constant outside"},
           {open + "struct A { double d; };\n", "p/msg/A.idl:1: module p::msg is not closed"},
           {open + "struct B { double d; };\n" + close, "p/msg/A.idl: defines no struct p::msg::A"},
           {"#include \"q/msg/Gone.idl\"\n" + open + "struct A { double d; };\n" + close,
            "p/msg/A.idl: #include \"q/msg/Gone.idl\": no loaded message library has this file"},
           {open + "struct A { string s = \"x; };\n" + close, "p/msg/A.idl:2: a string literal is not closed"},
           {open + "struct A { double d; }; /* open\n" + close, "p/msg/A.idl:2: a /* comment is not closed"},
       }) {
    EXPECT_EQ(errorOf("p/msg/A", {{"p/msg/A.idl", c.idl}}).rfind(c.error, 0), 0u)
        << "got: " << errorOf("p/msg/A", {{"p/msg/A.idl", c.idl}}) << "\nexpected: " << c.error;
  }
}

}  // namespace
}  // namespace uampc
