// Writer and Reader together: what is written is read back, field for field, with each
// compression and with chunk sizes from "a chunk per message" to "one chunk for the file"; messages
// come out in log_time order across chunks that overlap in time; topic and start-time filters.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mcap_test_files.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::test {
namespace {

// Three topics: /scan with large payloads, /state with small ones, and /late, whose log times run
// 250 ms behind its write order (received late), so that chunks overlap in time. Payload bytes
// are pseudo-random (some all zero), sizes vary, some are empty.
std::vector<Message> sampleMessages(int count) {
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<Message> messages;
  for (int i = 0; i < count; ++i) {
    Message m;
    const std::uint64_t now = 1'000'000'000ull + static_cast<std::uint64_t>(i) * 10'000'000ull;
    switch (i % 3) {
      case 0:
        m.topic = "/scan";
        m.data.resize(static_cast<std::size_t>(1000 + (i * 37) % 3000));
        break;
      case 1:
        m.topic = "/state";
        m.data.resize(static_cast<std::size_t>((i * 7) % 40));
        break;
      default:
        m.topic = "/late";
        m.data.resize(16);
        break;
    }
    m.log_time = m.topic == "/late" ? now - 250'000'000ull : now;
    if (i % 10 == 5) m.log_time = messages.back().log_time;  // equal log times: file order decides
    m.publish_time = m.log_time - 1000;
    m.sequence = static_cast<std::uint32_t>(i);
    if (i % 17 != 0) {
      for (auto& b : m.data) b = static_cast<std::uint8_t>(byte(rng));
    }
    messages.push_back(m);
  }
  return messages;
}

struct WrittenFile {
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<Message> messages;
};

WrittenFile writeSample(const std::string& path, WriterOptions options, int count) {
  WrittenFile file;
  Writer writer(path, options);
  const std::string binary_schema("with\0zero\xff bytes", 16);
  file.schemas = {{1, "sensor_msgs/msg/PointCloud2", "ros2msg", "std_msgs/Header header\nuint32 height\n"},
                  {2, "x/Binary", "x-custom", binary_schema}};
  for (const Schema& s : file.schemas) EXPECT_EQ(writer.addSchema(s.name, s.encoding, s.data), s.id);
  file.channels = {{1, 1, "/scan", "cdr", {{"offered_qos_profiles", "- history: 1\n"}, {"uampc", "1"}}},
                   {2, 2, "/state", "cdr", {}},
                   {3, 0, "/late", "x-schemaless", {{"k", ""}}}};
  for (const Channel& c : file.channels)
    EXPECT_EQ(writer.addChannel(c.schema_id, c.topic, c.message_encoding, c.metadata), c.id);
  file.messages = sampleMessages(count);
  for (const Message& m : file.messages) {
    const std::uint16_t channel = m.topic == "/scan" ? 1 : m.topic == "/state" ? 2 : 3;
    writer.write(channel, m.sequence, m.log_time, m.publish_time, m.data.data(), m.data.size());
  }
  writer.close();
  EXPECT_EQ(writer.bytesWritten(), fs::file_size(path));
  return file;
}

std::vector<Message> inLogTimeOrder(std::vector<Message> messages) {
  std::stable_sort(messages.begin(), messages.end(),
                   [](const Message& a, const Message& b) { return a.log_time < b.log_time; });
  return messages;
}

void expectSameDefinitions(const Reader& reader, const WrittenFile& written) {
  ASSERT_EQ(reader.schemas().size(), written.schemas.size());
  for (std::size_t i = 0; i < written.schemas.size(); ++i) {
    EXPECT_EQ(reader.schemas()[i].id, written.schemas[i].id);
    EXPECT_EQ(reader.schemas()[i].name, written.schemas[i].name);
    EXPECT_EQ(reader.schemas()[i].encoding, written.schemas[i].encoding);
    EXPECT_EQ(reader.schemas()[i].data, written.schemas[i].data);
  }
  ASSERT_EQ(reader.channels().size(), written.channels.size());
  for (std::size_t i = 0; i < written.channels.size(); ++i) {
    EXPECT_EQ(reader.channels()[i].id, written.channels[i].id);
    EXPECT_EQ(reader.channels()[i].schema_id, written.channels[i].schema_id);
    EXPECT_EQ(reader.channels()[i].topic, written.channels[i].topic);
    EXPECT_EQ(reader.channels()[i].message_encoding, written.channels[i].message_encoding);
    EXPECT_EQ(reader.channels()[i].metadata, written.channels[i].metadata);
  }
}

struct RoundTripCase {
  Compression compression;
  std::uint64_t chunk_size;
};

class RoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(RoundTrip, ReadsBackEverySchemaChannelAndMessageInLogTimeOrder) {
  TempDir dir("round_trip");
  const std::string path = dir.file("sample.mcap");
  WriterOptions options;
  options.compression = GetParam().compression;
  options.chunk_size = GetParam().chunk_size;
  options.library = "uampc test";
  const WrittenFile written = writeSample(path, options, 600);

  Reader reader(path);
  EXPECT_FALSE(reader.recovered());
  EXPECT_TRUE(reader.warnings().empty());
  expectSameDefinitions(reader, written);
  EXPECT_EQ(reader.messageCount(), written.messages.size());
  const std::vector<Message> expected = inLogTimeOrder(written.messages);
  EXPECT_EQ(reader.startTime(), expected.front().log_time);
  EXPECT_EQ(reader.endTime(), expected.back().log_time);
  EXPECT_TRUE(readAll(reader) == expected);

  // Chunk count as configured: one chunk per ~chunk_size bytes of records.
  const auto chunks = recordsWithOpcode(readBytes(path), kChunkOpcode);
  if (options.chunk_size <= 4096) {
    EXPECT_GT(chunks.size(), 100u);
  } else if (options.chunk_size >= 4 * 1024 * 1024) {
    EXPECT_EQ(chunks.size(), 1u);
  }
  const std::string name = options.compression == Compression::kZstd  ? "zstd"
                           : options.compression == Compression::kLz4 ? "lz4"
                                                                      : "";
  for (const TopRecord& chunk : chunks) EXPECT_EQ(chunkCompression(readBytes(path), chunk), name);
}

INSTANTIATE_TEST_SUITE_P(
    CompressionsAndChunkSizes, RoundTrip,
    ::testing::Values(RoundTripCase{Compression::kZstd, 4 * 1024 * 1024}, RoundTripCase{Compression::kZstd, 4096},
                      RoundTripCase{Compression::kZstd, 1}, RoundTripCase{Compression::kLz4, 4 * 1024 * 1024},
                      RoundTripCase{Compression::kLz4, 4096}, RoundTripCase{Compression::kNone, 4 * 1024 * 1024},
                      RoundTripCase{Compression::kNone, 4096}));

TEST(RoundTrip, SecondReadGivesTheSameMessages) {
  TempDir dir("twice");
  const std::string path = dir.file("twice.mcap");
  WriterOptions options;
  options.chunk_size = 8192;
  writeSample(path, options, 300);
  Reader reader(path);
  const auto first = readAll(reader);
  EXPECT_EQ(first.size(), 300u);
  EXPECT_TRUE(readAll(reader) == first);
}

TEST(RoundTrip, FiltersByTopicAndStartTimeAndStopsWhenAsked) {
  TempDir dir("filters");
  const std::string path = dir.file("filters.mcap");
  WriterOptions options;
  options.chunk_size = 4096;
  const WrittenFile written = writeSample(path, options, 600);
  Reader reader(path);

  const std::uint64_t start = 1'000'000'000ull + 3'000'000'000ull;
  std::vector<Message> expected;
  for (const Message& m : inLogTimeOrder(written.messages))
    if ((m.topic == "/late" || m.topic == "/state") && m.log_time >= start) expected.push_back(m);
  ASSERT_GT(expected.size(), 100u);
  EXPECT_TRUE(readAll(reader, {"/late", "/state"}, start) == expected);
  EXPECT_TRUE(readAll(reader, {"/no_such_topic"}).empty());

  int visited = 0;
  reader.forEachMessage({}, 0, [&](const MessageView&) { return ++visited < 7; });
  EXPECT_EQ(visited, 7);

  ASSERT_NE(reader.findChannel("/late"), nullptr);
  EXPECT_EQ(reader.findChannel("/late")->id, 3);
  EXPECT_EQ(reader.findChannel("/nothing"), nullptr);
}

TEST(RoundTrip, FileWithoutMessagesHasItsChannels) {
  TempDir dir("empty");
  const std::string path = dir.file("empty.mcap");
  {
    Writer writer(path, WriterOptions{});
    writer.addChannel(writer.addSchema("std_msgs/msg/Float64", "ros2msg", "float64 data\n"), "/x", "cdr");
  }  // the destructor closes the file
  Reader reader(path);
  EXPECT_FALSE(reader.recovered());
  EXPECT_EQ(reader.messageCount(), 0u);
  EXPECT_EQ(reader.startTime(), 0u);
  ASSERT_EQ(reader.channels().size(), 1u);
  EXPECT_EQ(reader.channels()[0].topic, "/x");
  EXPECT_TRUE(readAll(reader).empty());
}

TEST(RoundTrip, CloseIsIdempotentAndTheDestructorCloses) {
  TempDir dir("close");
  const std::string closed_twice = dir.file("closed_twice.mcap");
  const std::string destructed = dir.file("destructed.mcap");
  const Bytes payload = {1, 2, 3};
  {
    Writer writer(closed_twice, WriterOptions{});
    writer.write(writer.addChannel(0, "/a", "x"), 0, 5, 5, payload.data(), payload.size());
    writer.close();
    const std::uint64_t size = writer.bytesWritten();
    writer.close();
    EXPECT_EQ(writer.bytesWritten(), size);
    EXPECT_THROW(writer.write(1, 0, 6, 6, payload.data(), payload.size()), McapError);
  }
  {
    Writer writer(destructed, WriterOptions{});
    writer.write(writer.addChannel(0, "/a", "x"), 0, 5, 5, payload.data(), payload.size());
  }
  EXPECT_EQ(readBytes(closed_twice), readBytes(destructed));
  Reader reader(destructed);
  EXPECT_FALSE(reader.recovered());
  EXPECT_EQ(readAll(reader).size(), 1u);
}

// A chunk of zeros compresses over 64 times, which the reader refuses as a possible decompression
// bomb: the writer stores such a chunk uncompressed, so that the file still reads.
TEST(RoundTrip, ChunkCompressingOver64TimesIsStoredUncompressed) {
  TempDir dir("zeros");
  for (Compression compression : {Compression::kZstd, Compression::kLz4}) {
    const std::string path = dir.file("zeros.mcap");
    WriterOptions options;
    options.compression = compression;
    const Bytes zeros(320 * 1024, 0);
    const Bytes noise = [] {
      Bytes b(320 * 1024);
      std::mt19937 rng(1);
      for (auto& x : b) x = static_cast<std::uint8_t>(rng());
      return b;
    }();
    {
      Writer writer(path, options);
      const std::uint16_t channel = writer.addChannel(0, "/zeros", "x");
      for (int i = 0; i < 20; ++i)
        writer.write(channel, 0, static_cast<std::uint64_t>(i), 0, zeros.data(), zeros.size());
      writer.close();
      Writer second(dir.file("noise.mcap"), options);
      const std::uint16_t noisy = second.addChannel(0, "/noise", "x");
      second.write(noisy, 0, 1, 0, noise.data(), noise.size());
    }
    const Bytes bytes = readBytes(path);
    const auto chunks = recordsWithOpcode(bytes, kChunkOpcode);
    ASSERT_EQ(chunks.size(), 2u);
    EXPECT_EQ(chunkCompression(bytes, chunks[0]), "");
    Reader reader(path);
    const auto messages = readAll(reader);
    ASSERT_EQ(messages.size(), 20u);
    EXPECT_TRUE(messages[19].data == zeros);
    // Data that compresses less keeps its compression.
    const Bytes noisy = readBytes(dir.file("noise.mcap"));
    EXPECT_EQ(chunkCompression(noisy, recordsWithOpcode(noisy, kChunkOpcode).at(0)),
              compression == Compression::kZstd ? "zstd" : "lz4");
  }
}

// The worker thread of WriterOptions::background stores the same chunks in the same order: the file
// is the same, byte for byte, with many chunks in flight or one.
TEST(RoundTrip, BackgroundWriterWritesTheSameBytes) {
  TempDir dir("background");
  for (const Compression compression : {Compression::kZstd, Compression::kLz4, Compression::kNone}) {
    for (const std::uint64_t chunk_size : {std::uint64_t{1}, std::uint64_t{4096}, std::uint64_t{4 * 1024 * 1024}}) {
      WriterOptions options;
      options.compression = compression;
      options.chunk_size = chunk_size;
      writeSample(dir.file("inline.mcap"), options, 600);
      options.background = true;
      writeSample(dir.file("background.mcap"), options, 600);
      EXPECT_TRUE(readBytes(dir.file("inline.mcap")) == readBytes(dir.file("background.mcap")))
          << "compression " << static_cast<int>(compression) << ", chunk size " << chunk_size;
    }
  }
}

TEST(WriterErrors, NameTheFile) {
  TempDir dir("writer_errors");
  const std::string unwritable = dir.file("no_such_directory/x.mcap");
  try {
    Writer writer(unwritable, WriterOptions{});
    FAIL() << "a file in a missing directory was created";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find(unwritable), std::string::npos) << e.what();
  }
  Writer writer(dir.file("ok.mcap"), WriterOptions{});
  const Bytes payload = {1};
  EXPECT_THROW(writer.write(1, 0, 0, 0, payload.data(), payload.size()), McapError);  // no channel 1
  EXPECT_THROW(writer.addChannel(3, "/a", "cdr"), McapError);                         // no schema 3
}

class FullDisk : public ::testing::TestWithParam<bool> {};

// With a worker thread (GetParam()), its error reaches the caller at a later write() or at close(),
// and the writer neither hangs nor crashes.
TEST_P(FullDisk, IsAnErrorNamingTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const Bytes payload(64 * 1024, 7);
  try {
    WriterOptions options;
    options.background = GetParam();
    Writer writer("/dev/full", options);
    const std::uint16_t channel = writer.addChannel(0, "/a", "x");
    for (int i = 0; i < 200; ++i)
      writer.write(channel, 0, static_cast<std::uint64_t>(i), 0, payload.data(), payload.size());
    writer.close();
    FAIL() << "writing 12 MB to /dev/full succeeded";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(InlineAndBackground, FullDisk, ::testing::Bool());

}  // namespace
}  // namespace uampc::mcap::test
