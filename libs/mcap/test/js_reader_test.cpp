// Our MCAP files read by an independent reader, not only by our own (docs/user/topics-and-recordings.md):
// tests/mcap_js/read_mcap.mjs opens them with Foxglove's @mcap/core indexed reader and
// decodes every message with @foxglove/rosmsg2-serialization from the ros2msg schema in the file.
// The schemas (rosbag2's concatenated definitions) and the CDR bytes are written here by hand, so
// that the values the JS reader prints can only match if container, schema and CDR are all right.
//
// Needs node and `npm ci --prefix tests/mcap_js` (docker/install-deps.sh does both): without them
// the test fails, unless UAMPC_SKIP_JS=1 is set.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "mcap_test_files.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::test {
namespace {

using nlohmann::json;

const char* const kFloat64Definition = "float64 data\n";

const char* const kJointStateDefinition =
    "# This is a message that holds data to describe the state of a set of torque controlled joints.\n"
    "std_msgs/Header header\n"
    "\n"
    "string[] name\n"
    "float64[] position\n"
    "float64[] velocity\n"
    "float64[] effort\n"
    "\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "# Standard metadata for higher-level stamped data types.\n"
    "builtin_interfaces/Time stamp\n"
    "\n"
    "# Transform frame with which this data is associated.\n"
    "string frame_id\n"
    "\n"
    "================================================================================\n"
    "MSG: builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n";

// Plain CDR, little endian (encapsulation 00 01 00 00); a primitive is aligned to its size,
// counted from the end of the 4-byte encapsulation header.
class CdrBytes {
 public:
  CdrBytes() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  CdrBytes& u32(std::uint32_t v) { return put(&v, 4); }
  CdrBytes& i32(std::int32_t v) { return put(&v, 4); }
  CdrBytes& f64(double v) { return put(&v, 8); }
  CdrBytes& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
    return *this;
  }
  const Bytes& bytes() const { return bytes_; }

 private:
  CdrBytes& put(const void* v, std::size_t size) {  // this test runs on little-endian machines
    while ((bytes_.size() - 4) % size != 0) bytes_.push_back(0);
    const auto* p = static_cast<const std::uint8_t*>(v);
    bytes_.insert(bytes_.end(), p, p + size);
    return *this;
  }
  Bytes bytes_;
};

struct JointState {
  std::int32_t sec;
  std::uint32_t nanosec;
  std::string frame_id;
  std::vector<std::string> name;
  std::vector<double> position, velocity, effort;
};

Bytes jointStateCdr(const JointState& j) {
  CdrBytes cdr;
  cdr.i32(j.sec).u32(j.nanosec).str(j.frame_id);
  cdr.u32(static_cast<std::uint32_t>(j.name.size()));
  for (const auto& n : j.name) cdr.str(n);
  for (const auto* sequence : {&j.position, &j.velocity, &j.effort}) {
    cdr.u32(static_cast<std::uint32_t>(sequence->size()));
    for (double v : *sequence) cdr.f64(v);
  }
  return cdr.bytes();
}

Bytes float64Cdr(double value) {
  Bytes bytes = {0x00, 0x01, 0x00, 0x00, 0, 0, 0, 0, 0, 0, 0, 0};
  std::memcpy(bytes.data() + 4, &value, 8);
  return bytes;
}

const std::vector<double> kFloats = {0.1, -2.5, 1e-300, 3.141592653589793, 12345.678, 6.02214076e23};

const std::vector<JointState> kJointStates = {
    {17, 250000000, "base_link", {"rotor", "tilt"}, {0.5, -1.25}, {}, {1.5}},
    {18, 999999999, "", {}, {}, {2.0, 3.0, 4.0}, {}},
    {-3, 1, "motor_rotor_with_a_longer_frame_name", {"a"}, {1e-9}, {-1e9}, {0.0}},
};

// Float64 at 10 ms steps from 1 s, JointState at 15 ms steps from 1.005 s: interleaved in time.
void writeRecording(const std::string& path, Compression compression, std::uint64_t chunk_size,
                    const std::string& float64_schema = kFloat64Definition) {
  WriterOptions options;
  options.compression = compression;
  options.chunk_size = chunk_size;
  options.library = "uampc js_reader_test";
  Writer writer(path, options);
  const std::uint16_t f = writer.addChannel(writer.addSchema("std_msgs/msg/Float64", "ros2msg", float64_schema),
                                            "/float", "cdr", {{"offered_qos_profiles", ""}});
  const std::uint16_t j =
      writer.addChannel(writer.addSchema("sensor_msgs/msg/JointState", "ros2msg", kJointStateDefinition), "/joints",
                        "cdr", {{"offered_qos_profiles", ""}});
  for (std::size_t i = 0; i < kFloats.size(); ++i) {
    const Bytes cdr = float64Cdr(kFloats[i]);
    writer.write(f, static_cast<std::uint32_t>(i), 1'000'000'000ull + 10'000'000ull * i, 1'000'000'000ull, cdr.data(),
                 cdr.size());
  }
  for (std::size_t i = 0; i < kJointStates.size(); ++i) {
    const Bytes cdr = jointStateCdr(kJointStates[i]);
    writer.write(j, static_cast<std::uint32_t>(i), 1'005'000'000ull + 15'000'000ull * i, 1'000'000'000ull, cdr.data(),
                 cdr.size());
  }
}

struct NodeRun {
  int exit_code = -1;
  std::vector<json> lines;
  std::string stderr_text;
};

bool skipRequested() {
  const char* skip = std::getenv("UAMPC_SKIP_JS");
  return skip && std::string(skip) == "1";
}

// Fails the test (does not skip it) when node or the npm packages are missing.
void requireNode() {
  ASSERT_EQ(std::system("command -v node >/dev/null 2>&1"), 0)
      << "node is not installed (docker/install-deps.sh installs it; UAMPC_SKIP_JS=1 skips this test)";
  ASSERT_TRUE(fs::exists(fs::path(UAMPC_MCAP_JS_DIR) / "node_modules" / "@mcap" / "core"))
      << "run `npm ci --prefix tests/mcap_js` (docker/install-deps.sh does; UAMPC_SKIP_JS=1 skips this test)";
}

NodeRun readWithNode(const std::string& mcap, const std::string& stderr_file) {
  const std::string command =
      "node '" + std::string(UAMPC_MCAP_JS_DIR) + "/read_mcap.mjs' '" + mcap + "' 2>'" + stderr_file + "'";
  NodeRun run;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return run;
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) out.append(buffer, n);
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) run.lines.push_back(json::parse(line));
  std::ifstream err(stderr_file);
  run.stderr_text.assign(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  return run;
}

void expectJointState(const json& m, const JointState& j) {
  EXPECT_EQ(m["header"]["stamp"]["sec"].get<std::int32_t>(), j.sec);
  EXPECT_EQ(m["header"]["stamp"]["nanosec"].get<std::uint32_t>(), j.nanosec);
  EXPECT_EQ(m["header"]["frame_id"].get<std::string>(), j.frame_id);
  EXPECT_EQ(m["name"].get<std::vector<std::string>>(), j.name);
  EXPECT_EQ(m["position"].get<std::vector<double>>(), j.position);
  EXPECT_EQ(m["velocity"].get<std::vector<double>>(), j.velocity);
  EXPECT_EQ(m["effort"].get<std::vector<double>>(), j.effort);
}

struct Case {
  Compression compression;
  std::uint64_t chunk_size;
};

class JsReader : public ::testing::TestWithParam<Case> {};

TEST_P(JsReader, DecodesEveryMessageToTheValuesWritten) {
  if (skipRequested()) GTEST_SKIP() << "UAMPC_SKIP_JS=1";
  requireNode();
  TempDir dir("js_reader");
  const std::string path = dir.file("ros2.mcap");
  writeRecording(path, GetParam().compression, GetParam().chunk_size);

  const NodeRun run = readWithNode(path, dir.file("stderr.txt"));
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  ASSERT_EQ(run.lines.size(), kFloats.size() + kJointStates.size() + 1);

  std::size_t floats = 0, joints = 0;
  std::uint64_t previous_log_time = 0;
  for (std::size_t i = 0; i + 1 < run.lines.size(); ++i) {
    const json& line = run.lines[i];
    const std::uint64_t log_time = std::stoull(line["log_time"].get<std::string>());
    EXPECT_GE(log_time, previous_log_time);  // the JS reader's order is ours: by log time
    previous_log_time = log_time;
    if (line["topic"] == "/float") {
      ASSERT_LT(floats, kFloats.size());
      EXPECT_EQ(log_time, 1'000'000'000ull + 10'000'000ull * floats);
      EXPECT_EQ(line["sequence"].get<std::uint32_t>(), floats);
      EXPECT_EQ(line["message"]["data"].get<double>(), kFloats[floats]);
      ++floats;
    } else {
      ASSERT_EQ(line["topic"], "/joints");
      ASSERT_LT(joints, kJointStates.size());
      EXPECT_EQ(log_time, 1'005'000'000ull + 15'000'000ull * joints);
      expectJointState(line["message"], kJointStates[joints]);
      ++joints;
    }
  }
  EXPECT_EQ(floats, kFloats.size());
  EXPECT_EQ(joints, kJointStates.size());
  const json& summary = run.lines.back()["summary"];
  EXPECT_EQ(summary["profile"], "ros2");
  EXPECT_EQ(summary["library"], "uampc js_reader_test");
  EXPECT_EQ(summary["messages"], std::to_string(kFloats.size() + kJointStates.size()));
  if (GetParam().chunk_size < 100) {
    EXPECT_GT(summary["chunks"].get<int>(), 4);
  }
}

INSTANTIATE_TEST_SUITE_P(Compressions, JsReader,
                         ::testing::Values(Case{Compression::kZstd, 4 * 1024 * 1024}, Case{Compression::kZstd, 64},
                                           Case{Compression::kLz4, 4 * 1024 * 1024}, Case{Compression::kLz4, 64},
                                           Case{Compression::kNone, 64}));

// The JS reader is not vacuous: a damaged chunk, or a schema that does not describe the bytes,
// makes it fail.
TEST(JsReaderChecks, FailsOnADamagedChunkOrAWrongSchema) {
  if (skipRequested()) GTEST_SKIP() << "UAMPC_SKIP_JS=1";
  requireNode();
  TempDir dir("js_reader_checks");
  const std::string damaged = dir.file("damaged.mcap");
  writeRecording(damaged, Compression::kNone, 64);
  Bytes bytes = readBytes(damaged);
  const TopRecord chunk = recordsWithOpcode(bytes, kChunkOpcode).at(2);
  bytes[chunk.end() - 3] ^= 0x20;  // inside a message's data: only the CRC can tell
  writeBytes(damaged, bytes);
  NodeRun run = readWithNode(damaged, dir.file("stderr.txt"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.stderr_text.find("CRC"), std::string::npos) << run.stderr_text;

  const std::string wrong = dir.file("wrong_schema.mcap");
  writeRecording(wrong, Compression::kZstd, 1024, "float32 data\n");
  run = readWithNode(wrong, dir.file("stderr.txt"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.stderr_text.find("bytes left after decoding"), std::string::npos) << run.stderr_text;
}

}  // namespace
}  // namespace uampc::mcap::test
