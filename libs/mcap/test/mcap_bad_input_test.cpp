// Bad input: an error naming the file (and the record's byte offset when there is one), never a
// crash, never an allocation the file does not justify. Also: records of unknown opcode are
// skipped, as the spec requires.
#include <gtest/gtest.h>

#include <random>
#include <typeinfo>

#include "mcap_test_files.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::test {
namespace {

// The error `read` throws, or "" when it throws none.
template <typename Read>
std::string errorOf(Read read) {
  try {
    read();
  } catch (const McapError& e) {
    return e.what();
  }
  return "";
}

void readEverything(const std::string& path) {
  Reader reader(path);
  reader.forEachMessage({}, 0, [](const MessageView&) { return true; });
}

// A small indexed file: 40 messages in chunks of about 1 KB.
Bytes smallFile(const std::string& path, Compression compression) {
  WriterOptions options;
  options.compression = compression;
  options.chunk_size = 1024;
  Writer writer(path, options);
  const std::uint16_t channel = writer.addChannel(writer.addSchema("x/A", "ros2msg", "uint8[] data\n"), "/a", "cdr");
  std::mt19937 rng(3);
  for (int i = 0; i < 40; ++i) {
    Bytes data(200 + static_cast<std::size_t>(i));
    for (auto& b : data) b = static_cast<std::uint8_t>(rng() % 16);  // compressible, not trivially
    writer.write(channel, static_cast<std::uint32_t>(i), 1000 + static_cast<std::uint64_t>(i), 0, data.data(),
                 data.size());
  }
  writer.close();
  return readBytes(path);
}

TEST(BadInput, EmptyFile) {
  TempDir dir("empty_file");
  const std::string path = dir.file("empty.mcap");
  writeBytes(path, {});
  const std::string error = errorOf([&] { Reader reader(path); });
  EXPECT_EQ(error, path + ": empty file, not an MCAP file");
}

TEST(BadInput, NotAnMcapFile) {
  TempDir dir("not_mcap");
  const std::string path = dir.file("scene.yaml");
  const std::string text = "components:\n  - type: raycaster\n";
  writeBytes(path, Bytes(text.begin(), text.end()));
  EXPECT_EQ(errorOf([&] { Reader reader(path); }),
            path + ": not an MCAP file (it does not start with the MCAP magic bytes)");
  writeBytes(path, Bytes{0x89, 'M', 'C'});  // shorter than the magic
  EXPECT_NE(errorOf([&] { Reader reader(path); }).find("not an MCAP file"), std::string::npos);
  EXPECT_NE(errorOf([&] { Reader reader(dir.file("missing.mcap")); }).find(dir.file("missing.mcap") + ": cannot open"),
            std::string::npos);
}

TEST(BadInput, HeaderCutOffOrHuge) {
  TempDir dir("header");
  const std::string path = dir.file("h.mcap");
  const Bytes whole = smallFile(path, Compression::kZstd);
  writeBytes(path, Bytes(whole.begin(), whole.begin() + 12));
  EXPECT_EQ(errorOf([&] { Reader reader(path); }), path + ": record at byte 8: the Header record is cut off");
  Bytes huge = whole;
  setU64(huge, 9, std::uint64_t{1} << 60);
  writeBytes(path, huge);
  EXPECT_NE(errorOf([&] { Reader reader(path); }).find(path + ": record at byte 8: the Header record declares"),
            std::string::npos);
}

// A single-bit change (bits 0, 4, 7 of every byte) anywhere in a chunk record of an indexed file is an error naming the
// file and the chunk's offset (its header fields are checked against the chunk index, its records
// by the CRC or the decompressor), or, where the compressed stream decodes to the same records
// (a match offset that points at equal bytes), the messages are read unchanged: never silently
// different data. Uncompressed, every change is an error.
TEST(BadInput, EveryFlippedBitInAChunkIsAnErrorWithItsOffsetOrChangesNothing) {
  TempDir dir("flipped");
  for (Compression compression : {Compression::kZstd, Compression::kLz4, Compression::kNone}) {
    const std::string original = dir.file("original.mcap");
    const Bytes whole = smallFile(original, compression);
    Reader intact(original);
    const std::vector<Message> messages = readAll(intact);
    const auto chunks = recordsWithOpcode(whole, kChunkOpcode);
    ASSERT_GT(chunks.size(), 4u);
    const TopRecord& chunk = chunks[2];
    const std::string path = dir.file("flipped.mcap");
    const std::string expected = path + ": record at byte " + std::to_string(chunk.offset) + ": ";
    std::size_t errors = 0;
    for (std::uint64_t at = chunk.offset; at < chunk.end(); ++at) {
      for (int bit : {0, 4, 7}) {
        Bytes flipped = whole;
        flipped[at] ^= static_cast<std::uint8_t>(1 << bit);
        writeBytes(path, flipped);
        std::vector<Message> read;
        const std::string error = errorOf([&] {
          Reader reader(path);
          read = readAll(reader);
        });
        if (error.empty()) {
          ASSERT_TRUE(compression != Compression::kNone && read == messages) << "bit " << bit << " of byte " << at;
        } else {
          ASSERT_EQ(error.rfind(expected, 0), 0u) << "bit " << bit << " of byte " << at << ": '" << error << "'";
          ++errors;
        }
      }
    }
    EXPECT_GT(errors, 3 * (chunk.end() - chunk.offset) * 9 / 10);  // decoding to equal records is rare
  }
}

TEST(BadInput, HugeChunkLengthInAnIndexedFile) {
  TempDir dir("huge_chunk");
  const std::string path = dir.file("huge.mcap");
  Bytes bytes = smallFile(path, Compression::kZstd);
  const TopRecord chunk = recordsWithOpcode(bytes, kChunkOpcode).at(1);
  setU64(bytes, chunk.offset + 1, std::uint64_t{1} << 62);
  writeBytes(path, bytes);
  const std::string error = errorOf([&] { readEverything(path); });
  EXPECT_EQ(error.rfind(path + ": record at byte " + std::to_string(chunk.offset) + ": ", 0), 0u) << error;
}

// Sets what a chunk declares as its uncompressed size in the chunk and in its index (and drops the
// summary CRC, 0 meaning "none"), so that only the size limits can refuse it.
Bytes declareUncompressedSize(Bytes bytes, std::size_t chunk_number, std::uint64_t size, TopRecord& chunk) {
  chunk = recordsWithOpcode(bytes, kChunkOpcode).at(chunk_number);
  setU64(bytes, chunk.offset + 9 + 16, size);
  const TopRecord index = recordsWithOpcode(bytes, kChunkIndexOpcode).at(chunk_number);
  setU64(bytes, index.end() - 8, size);  // uncompressed_size is the chunk index's last field
  setU32(bytes, bytes.size() - 8 - 4, 0);
  return bytes;
}

TEST(BadInput, ChunkDeclaringOver1GiBOrOver64TimesItsSizeIsRefused) {
  TempDir dir("bomb");
  const std::string path = dir.file("bomb.mcap");
  const Bytes whole = smallFile(path, Compression::kZstd);
  TopRecord chunk;
  writeBytes(path, declareUncompressedSize(whole, 1, std::uint64_t{1} << 40, chunk));
  std::string error = errorOf([&] { readEverything(path); });
  EXPECT_EQ(error.rfind(path + ": record at byte " + std::to_string(chunk.offset) + ": ", 0), 0u) << error;
  EXPECT_NE(error.find("over the 1 GiB"), std::string::npos) << error;

  const std::uint64_t compressed = getU64(whole, chunk.offset + 9 + 28 + 4 + 4);  // after "zstd"
  writeBytes(path, declareUncompressedSize(whole, 1, compressed * 64 + 1, chunk));
  error = errorOf([&] { readEverything(path); });
  EXPECT_NE(error.find("over 64 times"), std::string::npos) << error;

  // At exactly 64 times the limits pass, and the decompressor finds the size wrong.
  writeBytes(path, declareUncompressedSize(whole, 1, compressed * 64, chunk));
  error = errorOf([&] { readEverything(path); });
  EXPECT_NE(error.find("zstd data"), std::string::npos) << error;
}

// Sets a field inside an uncompressed chunk's records (the chunk's CRC dropped), so that the
// records themselves are what is wrong.
TEST(BadInput, RecordInsideAChunkRunningPastItsEnd) {
  TempDir dir("inner");
  const std::string path = dir.file("inner.mcap");
  Bytes bytes = smallFile(path, Compression::kNone);
  const TopRecord chunk = recordsWithOpcode(bytes, kChunkOpcode).at(1);
  setU32(bytes, chunk.offset + 9 + 24, 0);                        // uncompressed_crc 0: no CRC
  const std::size_t records = chunk.offset + 9 + 28 + 4 + 0 + 8;  // compression "" then records length
  setU64(bytes, records + 1, std::uint64_t{1} << 50);             // the first record's length
  writeBytes(path, bytes);
  const std::string error = errorOf([&] { readEverything(path); });
  EXPECT_EQ(error.rfind(path + ": record at byte " + std::to_string(chunk.offset) + ": ", 0), 0u) << error;
  EXPECT_NE(error.find("declares"), std::string::npos) << error;
}

// A file written here record by record from the spec: a record of opcode 0x80 (an application
// extension) before the chunk and inside it, and an unknown 0x7E; the reader skips all three.
// The file has a footer without summary (summary_start 0), which the spec allows.
TEST(BadInput, RecordsOfUnknownOpcodeAreSkipped) {
  auto u16 = [](Bytes& b, std::uint16_t v) {
    b.push_back(static_cast<std::uint8_t>(v));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
  };
  auto u32 = [](Bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  auto u64 = [](Bytes& b, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  auto str = [&](Bytes& b, const std::string& s) {
    u32(b, static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  };
  auto record = [&](Bytes& b, std::uint8_t opcode, const Bytes& content) {
    b.push_back(opcode);
    u64(b, content.size());
    b.insert(b.end(), content.begin(), content.end());
  };
  const Bytes magic = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
  Bytes header, unknown = {1, 2, 3}, channel, message, records, chunk, data_end, footer;
  str(header, "ros2");
  str(header, "hand");
  u16(channel, 1);
  u16(channel, 0);
  str(channel, "/hand");
  str(channel, "x");
  u32(channel, 0);  // no metadata
  u16(message, 1);
  u32(message, 7);
  u64(message, 42);
  u64(message, 41);
  message.insert(message.end(), {9, 8, 7});
  record(records, 0x04, channel);
  record(records, 0x80, unknown);
  record(records, 0x05, message);
  u64(chunk, 42);
  u64(chunk, 42);
  u64(chunk, records.size());
  u32(chunk, 0);
  str(chunk, "");
  u64(chunk, records.size());
  chunk.insert(chunk.end(), records.begin(), records.end());
  u32(data_end, 0);
  u64(footer, 0);
  u64(footer, 0);
  u32(footer, 0);
  Bytes file = magic;
  record(file, 0x01, header);
  record(file, 0x80, unknown);
  record(file, 0x06, chunk);
  record(file, 0x7E, unknown);
  record(file, 0x0F, data_end);
  record(file, 0x02, footer);
  file.insert(file.end(), magic.begin(), magic.end());

  TempDir dir("unknown_opcode");
  const std::string path = dir.file("hand.mcap");
  writeBytes(path, file);
  Reader reader(path);
  ASSERT_EQ(reader.channels().size(), 1u);
  const auto messages = readAll(reader);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].topic, "/hand");
  EXPECT_EQ(messages[0].sequence, 7u);
  EXPECT_EQ(messages[0].log_time, 42u);
  EXPECT_EQ(messages[0].publish_time, 41u);
  EXPECT_EQ(messages[0].data, (Bytes{9, 8, 7}));
}

// A footer whose summary CRC does not match: the summary is not trusted, the file is scanned.
TEST(BadInput, DamagedSummaryIsNotTrusted) {
  TempDir dir("summary");
  const std::string path = dir.file("s.mcap");
  Bytes bytes = smallFile(path, Compression::kLz4);
  Reader intact(path);
  const auto expected = readAll(intact);
  const TopRecord index = recordsWithOpcode(bytes, kChunkIndexOpcode).at(0);
  bytes[index.offset + 9 + 16] ^= 0x10;  // the first chunk index's chunk_start_offset
  writeBytes(path, bytes);
  Reader reader(path);
  EXPECT_TRUE(reader.recovered());
  ASSERT_EQ(reader.warnings().size(), 1u);
  EXPECT_NE(reader.warnings()[0].find(path + ": its summary does not match the footer's CRC"), std::string::npos)
      << reader.warnings()[0];
  EXPECT_TRUE(readAll(reader) == expected);

  // Without a summary CRC (0), a chunk index pointing past the data section is caught by itself.
  bytes = readBytes(path);
  bytes[index.offset + 9 + 16] ^= 0x10;  // undo the damage
  setU64(bytes, index.offset + 9 + 16, bytes.size() + 100);
  setU32(bytes, bytes.size() - 8 - 4, 0);
  writeBytes(path, bytes);
  Reader unchecked(path);
  EXPECT_TRUE(unchecked.recovered());
  EXPECT_NE(unchecked.warnings().at(0).find("a chunk index points outside the data section"), std::string::npos)
      << unchecked.warnings()[0];
  EXPECT_TRUE(readAll(unchecked) == expected);
}

// Random damage (bytes overwritten anywhere, the file cut anywhere, with and without its footer)
// is either read or refused with an McapError; never another exception, a crash or a hang.
TEST(BadInput, RandomDamageIsReadOrRefusedWithAnMcapError) {
  TempDir dir("random_damage");
  const std::string original = dir.file("original.mcap");
  const Bytes whole = smallFile(original, Compression::kLz4);
  const std::string path = dir.file("damaged.mcap");
  std::mt19937 rng(2024);
  int refused = 0, read = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Bytes bytes = whole;
    const int damaged_bytes = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < damaged_bytes; ++k) bytes[rng() % bytes.size()] = static_cast<std::uint8_t>(rng());
    if (trial % 2 == 1) bytes.resize(rng() % bytes.size());
    writeBytes(path, bytes);
    try {
      Reader reader(path);
      readAll(reader);
      ++read;
    } catch (const McapError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << ": " << typeid(e).name() << ": " << e.what();
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(read, 0);
}

}  // namespace
}  // namespace uampc::mcap::test
