// MCAP write and read throughput for 320 KB messages (a 20k-point scan of x, y, z, intensity as
// float32, the size of a Mid-360 frame at 10 Hz), with zstd, lz4 and no compression, default 4 MiB
// chunks. Writing goes to /dev/null so that it measures what the recorder's thread spends
// (encoding, CRC, compression), not the disk; reading opens a file of 256 scans in the temp dir
// (80 MB) with a new Reader each time, as `uampc play` reads a recording once.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap {
namespace {

constexpr int kPoints = 20000;
constexpr int kScansInReadFile = 256;  // 80 MB: 20 chunks, more than the reader caches

// Points on the ground and on a wall around a sensor, with 2 cm noise: about as compressible as
// a real scan (float32 mantissas are mostly noise).
std::vector<std::uint8_t> makeScan(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(kPoints) * 16);
  for (int i = 0; i < kPoints; ++i) {
    const float a = 6.2831853f * unit(rng);
    const bool ground = i % 2 == 0;
    const float r = ground ? 30.0f * std::sqrt(unit(rng)) : 20.0f;
    const float point[4] = {r * std::cos(a) + noise(rng), r * std::sin(a) + noise(rng),
                            ground ? -1.5f + noise(rng) : 8.0f * unit(rng), std::floor(255.0f * unit(rng))};
    std::memcpy(bytes.data() + static_cast<std::size_t>(i) * 16, point, 16);
  }
  return bytes;
}

const std::vector<std::vector<std::uint8_t>>& scans() {
  static const std::vector<std::vector<std::uint8_t>> s = [] {
    std::vector<std::vector<std::uint8_t>> v;
    for (unsigned k = 0; k < 8; ++k) v.push_back(makeScan(k));
    return v;
  }();
  return s;
}

Compression compressionOf(const benchmark::State& state) { return static_cast<Compression>(state.range(0)); }

void BM_Write(benchmark::State& state) {
  WriterOptions options;
  options.compression = compressionOf(state);
  Writer writer("/dev/null", options);
  const std::uint16_t channel =
      writer.addChannel(writer.addSchema("sensor_msgs/msg/PointCloud2", "ros2msg", ""), "/lidar/points", "cdr");
  std::uint64_t t = 0;
  for (auto _ : state) {
    const auto& scan = scans()[t % scans().size()];
    writer.write(channel, static_cast<std::uint32_t>(t), t * 100'000'000ull, t * 100'000'000ull, scan.data(),
                 scan.size());
    ++t;
  }
  writer.close();
  const double in = static_cast<double>(t) * static_cast<double>(scans()[0].size());
  state.SetBytesProcessed(static_cast<std::int64_t>(in));
  state.counters["file/input"] = static_cast<double>(writer.bytesWritten()) / in;
}

std::string readFile(Compression compression) {
  const auto path =
      std::filesystem::temp_directory_path() / ("uampc_mcap_bench_" + std::to_string(static_cast<int>(compression)) +
                                                "_" + std::to_string(::getpid()) + ".mcap");
  WriterOptions options;
  options.compression = compression;
  Writer writer(path.string(), options);
  const std::uint16_t channel =
      writer.addChannel(writer.addSchema("sensor_msgs/msg/PointCloud2", "ros2msg", ""), "/lidar/points", "cdr");
  for (int k = 0; k < kScansInReadFile; ++k) {
    const auto& scan = scans()[static_cast<std::size_t>(k) % scans().size()];
    writer.write(channel, static_cast<std::uint32_t>(k), static_cast<std::uint64_t>(k) * 100'000'000ull, 0, scan.data(),
                 scan.size());
  }
  writer.close();
  return path.string();
}

void BM_Read(benchmark::State& state) {
  const std::string path = readFile(compressionOf(state));
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    Reader reader(path);
    reader.forEachMessage({}, 0, [&](const MessageView& m) {
      benchmark::DoNotOptimize(m.data[m.size - 1]);
      bytes += m.size;
      return true;
    });
  }
  std::filesystem::remove(path);
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}

void compressions(benchmark::internal::Benchmark* b) {
  b->ArgName("compression")
      ->Arg(static_cast<int>(Compression::kZstd))
      ->Arg(static_cast<int>(Compression::kLz4))
      ->Arg(static_cast<int>(Compression::kNone));
}

BENCHMARK(BM_Write)->Apply(compressions)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Read)->Apply(compressions)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace uampc::mcap

BENCHMARK_MAIN();
