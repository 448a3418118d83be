// Files whose writer did not finish: cut off at every tenth of their length, or left by a writer
// killed with SIGKILL. The reader scans them and returns exactly the messages of the chunks that
// are complete, which the test knows independently: chunk boundaries from its own walk over the
// file's records, and which messages each chunk holds from when bytesWritten() grew while writing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <random>

#include "mcap_test_files.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::test {
namespace {

struct RecordedFile {
  Bytes bytes;
  std::vector<Message> messages;            // in write order
  std::vector<std::size_t> chunk_messages;  // how many messages each chunk holds, in file order
};

Message messageNumber(int i) {
  Message m;
  m.topic = i % 2 == 0 ? "/points" : "/motor";
  m.sequence = static_cast<std::uint32_t>(i);
  // /motor runs 30 ms late: chunks overlap in time.
  m.log_time = 5'000'000'000ull + static_cast<std::uint64_t>(i) * 10'000'000ull - (i % 2 == 0 ? 0 : 30'000'000ull);
  m.publish_time = m.log_time;
  m.data.resize(i % 2 == 0 ? 2000 : 24);
  std::mt19937 rng(static_cast<std::uint32_t>(i));
  for (auto& b : m.data) b = static_cast<std::uint8_t>(rng());
  return m;
}

// Writes `count` messages; a chunk is written when bytesWritten() grows, and holds the messages
// written since the previous one (the last chunk is written by close()).
RecordedFile record(const std::string& path, Compression compression, int count) {
  RecordedFile file;
  WriterOptions options;
  options.compression = compression;
  options.chunk_size = 16 * 1024;
  Writer writer(path, options);
  const std::uint16_t schema = writer.addSchema("x/Points", "ros2msg", "uint8[] data\n");
  const std::uint16_t points = writer.addChannel(schema, "/points", "cdr");
  const std::uint16_t motor = writer.addChannel(schema, "/motor", "cdr");
  std::size_t unflushed = 0;
  for (int i = 0; i < count; ++i) {
    const Message m = messageNumber(i);
    const std::uint64_t before = writer.bytesWritten();
    writer.write(m.topic == "/points" ? points : motor, m.sequence, m.log_time, m.publish_time, m.data.data(),
                 m.data.size());
    file.messages.push_back(m);
    ++unflushed;
    if (writer.bytesWritten() > before) {
      file.chunk_messages.push_back(unflushed);
      unflushed = 0;
    }
  }
  writer.close();
  if (unflushed > 0) file.chunk_messages.push_back(unflushed);
  file.bytes = readBytes(path);
  return file;
}

// The messages of the chunks that lie wholly within the first `length` bytes, in log-time order.
std::vector<Message> messagesOfCompleteChunks(const RecordedFile& file, std::uint64_t length) {
  const auto chunks = recordsWithOpcode(file.bytes, kChunkOpcode);
  EXPECT_EQ(chunks.size(), file.chunk_messages.size());
  std::vector<Message> kept;
  std::size_t first = 0;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    if (chunks[c].end() <= length) {
      kept.insert(kept.end(), file.messages.begin() + static_cast<std::ptrdiff_t>(first),
                  file.messages.begin() + static_cast<std::ptrdiff_t>(first + file.chunk_messages[c]));
    }
    first += file.chunk_messages[c];
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Message& a, const Message& b) { return a.log_time < b.log_time; });
  return kept;
}

class Truncated : public ::testing::TestWithParam<Compression> {};

TEST_P(Truncated, AtEveryTenthYieldsExactlyTheMessagesOfTheCompleteChunks) {
  TempDir dir("truncated");
  const RecordedFile file = record(dir.file("whole.mcap"), GetParam(), 400);
  ASSERT_GT(file.chunk_messages.size(), 15u);
  for (int tenth = 1; tenth <= 10; ++tenth) {
    SCOPED_TRACE("cut at " + std::to_string(tenth) + "/10");
    const std::uint64_t length = file.bytes.size() * static_cast<std::uint64_t>(tenth) / 10;
    const std::string path = dir.file("cut" + std::to_string(tenth) + ".mcap");
    writeBytes(path, Bytes(file.bytes.begin(), file.bytes.begin() + static_cast<std::ptrdiff_t>(length)));

    Reader reader(path);
    const std::vector<Message> expected = messagesOfCompleteChunks(file, length);
    EXPECT_EQ(reader.recovered(), tenth < 10);
    if (tenth < 10) {
      ASSERT_FALSE(reader.warnings().empty());
      EXPECT_NE(reader.warnings().back().find(path + ": record at byte "), std::string::npos)
          << reader.warnings().back();
    }
    EXPECT_EQ(reader.messageCount(), expected.size());
    EXPECT_EQ(reader.channels().size(), expected.empty() ? 0u : 2u);  // channels come with the chunks
    const std::vector<Message> read = readAll(reader);
    EXPECT_EQ(read.size(), expected.size());
    EXPECT_TRUE(read == expected);
    if (!expected.empty()) {
      EXPECT_EQ(reader.startTime(), expected.front().log_time);
      EXPECT_EQ(reader.endTime(), expected.back().log_time);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Compressions, Truncated,
                         ::testing::Values(Compression::kZstd, Compression::kLz4, Compression::kNone));

// Without a footer, a damaged chunk ends the scan: the chunks before it are read, a warning names
// the damaged chunk's offset, and nothing after it is trusted.
TEST(Recovery, StopsAtTheFirstDamagedChunk) {
  TempDir dir("damaged");
  const RecordedFile file = record(dir.file("whole.mcap"), Compression::kZstd, 300);
  const auto chunks = recordsWithOpcode(file.bytes, kChunkOpcode);
  ASSERT_GT(chunks.size(), 6u);
  Bytes cut(file.bytes.begin(), file.bytes.begin() + static_cast<std::ptrdiff_t>(chunks.back().end()));
  const TopRecord& damaged = chunks[4];
  cut[damaged.offset + damaged.content_length / 2] ^= 0x40;
  const std::string path = dir.file("damaged.mcap");
  writeBytes(path, cut);

  Reader reader(path);
  EXPECT_TRUE(reader.recovered());
  ASSERT_FALSE(reader.warnings().empty());
  EXPECT_NE(reader.warnings().back().find(path + ": record at byte " + std::to_string(damaged.offset) + ":"),
            std::string::npos)
      << reader.warnings().back();
  EXPECT_TRUE(readAll(reader) == messagesOfCompleteChunks(file, damaged.offset));
}

// A chunk's record length running past the end of a file without footer is how a cut-off chunk
// looks: the scan stops there without allocating what the length declares.
TEST(Recovery, HugeRecordLengthEndsTheScan) {
  TempDir dir("huge_scan");
  const RecordedFile file = record(dir.file("whole.mcap"), Compression::kLz4, 200);
  const auto chunks = recordsWithOpcode(file.bytes, kChunkOpcode);
  Bytes cut(file.bytes.begin(), file.bytes.begin() + static_cast<std::ptrdiff_t>(chunks.back().end()));
  setU64(cut, chunks[2].offset + 1, std::uint64_t{1} << 62);
  const std::string path = dir.file("huge.mcap");
  writeBytes(path, cut);
  Reader reader(path);
  EXPECT_TRUE(reader.recovered());
  EXPECT_NE(reader.warnings().back().find("record at byte " + std::to_string(chunks[2].offset)), std::string::npos);
  EXPECT_TRUE(readAll(reader) == messagesOfCompleteChunks(file, chunks[2].offset));
}

// A writer killed with SIGKILL (no close(), no destructor): every chunk it wrote before is read.
// The child says through a pipe how many messages its written chunks hold, then waits to be
// killed; what it still buffers for the next chunk is lost.
TEST(Recovery, WriterKilledWithSigkillLeavesItsChunksReadable) {
  TempDir dir("sigkill");
  const std::string path = dir.file("killed.mcap");
  constexpr int kChunksBeforeKill = 5;
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    WriterOptions options;
    options.chunk_size = 16 * 1024;
    Writer writer(path, options);
    const std::uint16_t schema = writer.addSchema("x/Points", "ros2msg", "uint8[] data\n");
    const std::uint16_t points = writer.addChannel(schema, "/points", "cdr");
    const std::uint16_t motor = writer.addChannel(schema, "/motor", "cdr");
    std::uint64_t in_chunks = 0;
    int chunks = 0;
    for (int i = 0; chunks < kChunksBeforeKill; ++i) {
      const Message m = messageNumber(i);
      const std::uint64_t before = writer.bytesWritten();
      writer.write(m.topic == "/points" ? points : motor, m.sequence, m.log_time, m.publish_time, m.data.data(),
                   m.data.size());
      if (writer.bytesWritten() > before) {
        in_chunks = static_cast<std::uint64_t>(i) + 1;
        ++chunks;
      }
    }
    const Message unflushed = messageNumber(9999);  // buffered for the next chunk, never written
    writer.write(points, 9999, unflushed.log_time, 0, unflushed.data.data(), unflushed.data.size());
    if (::write(pipe_fds[1], &in_chunks, sizeof(in_chunks)) != sizeof(in_chunks)) ::_exit(3);
    while (true) ::pause();
  }
  ::close(pipe_fds[1]);
  std::uint64_t in_chunks = 0;
  const ssize_t n = ::read(pipe_fds[0], &in_chunks, sizeof(in_chunks));
  ::close(pipe_fds[0]);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_EQ(n, static_cast<ssize_t>(sizeof(in_chunks)));
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  Reader reader(path);
  EXPECT_TRUE(reader.recovered());
  std::vector<Message> expected;
  for (std::uint64_t i = 0; i < in_chunks; ++i) expected.push_back(messageNumber(static_cast<int>(i)));
  std::stable_sort(expected.begin(), expected.end(),
                   [](const Message& a, const Message& b) { return a.log_time < b.log_time; });
  EXPECT_EQ(reader.messageCount(), in_chunks);
  EXPECT_TRUE(readAll(reader) == expected);
}

}  // namespace
}  // namespace uampc::mcap::test
