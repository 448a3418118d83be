// What the MCAP tests share: a temporary directory per test, files as bytes, a list of the
// messages written (the expectation), and a walk over a file's top-level records written here
// from the spec, independently of the library's reader, so that tests know where chunks are.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::test {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("uampc_mcap_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline Bytes readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

inline std::uint64_t getU64(const Bytes& b, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | b.at(at + static_cast<std::size_t>(i));
  return v;
}

inline std::uint32_t getU32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b.at(at) | b.at(at + 1) << 8 | b.at(at + 2) << 16 |
                                    static_cast<std::uint32_t>(b.at(at + 3)) << 24);
}

inline void setU64(Bytes& b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) b.at(at + i) = static_cast<std::uint8_t>(v >> (8 * i));
}

inline void setU32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b.at(at + i) = static_cast<std::uint8_t>(v >> (8 * i));
}

// A top-level record: opcode, where its opcode byte is, and the length of its content.
struct TopRecord {
  std::uint8_t opcode = 0;
  std::uint64_t offset = 0;
  std::uint64_t content_length = 0;
  std::uint64_t end() const { return offset + 9 + content_length; }
};

constexpr std::uint8_t kChunkOpcode = 0x06;
constexpr std::uint8_t kChunkIndexOpcode = 0x08;
constexpr std::uint8_t kFooterOpcode = 0x02;

// Every record after the magic up to and including the footer (spec: "File Structure").
inline std::vector<TopRecord> topLevelRecords(const Bytes& file) {
  std::vector<TopRecord> records;
  std::uint64_t at = 8;
  while (at + 9 <= file.size()) {
    TopRecord r{file[at], at, getU64(file, at + 1)};
    if (r.end() > file.size()) throw std::runtime_error("test walk: record past the end of the file");
    records.push_back(r);
    if (r.opcode == kFooterOpcode) break;
    at = r.end();
  }
  return records;
}

inline std::vector<TopRecord> recordsWithOpcode(const Bytes& file, std::uint8_t opcode) {
  std::vector<TopRecord> out;
  for (const TopRecord& r : topLevelRecords(file))
    if (r.opcode == opcode) out.push_back(r);
  return out;
}

// A Chunk record's compression field (after start, end, uncompressed_size, uncompressed_crc).
inline std::string chunkCompression(const Bytes& file, const TopRecord& chunk) {
  const std::size_t at = chunk.offset + 9 + 28;
  const std::uint32_t length = getU32(file, at);
  return std::string(file.begin() + static_cast<std::ptrdiff_t>(at + 4),
                     file.begin() + static_cast<std::ptrdiff_t>(at + 4 + length));
}

// A message as written and as read back.
struct Message {
  std::string topic;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  Bytes data;
  bool operator==(const Message& o) const {
    return topic == o.topic && sequence == o.sequence && log_time == o.log_time && publish_time == o.publish_time &&
           data == o.data;
  }
};

inline std::vector<Message> readAll(Reader& reader, const std::vector<std::string>& topics = {},
                                    std::uint64_t start_ns = 0) {
  std::vector<Message> out;
  reader.forEachMessage(topics, start_ns, [&](const MessageView& m) {
    out.push_back({m.channel->topic, m.sequence, m.log_time, m.publish_time, Bytes(m.data, m.data + m.size)});
    return true;
  });
  return out;
}

}  // namespace uampc::mcap::test
