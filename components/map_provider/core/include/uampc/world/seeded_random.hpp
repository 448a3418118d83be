// Deterministic random numbers, identical on every standard library.
//
// std::mt19937_64's output sequence is fixed by the C++ standard, but std::uniform_*_distribution
// and std::normal_distribution are not: libstdc++ and libc++ map the same raw numbers to different
// values. So the mapping from raw 64-bit words to numbers is written out here.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace uampc::world {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1), from the top 53 bits of one raw word.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  // Integer uniform in [lo, hi] (inclusive); the tiny modulo bias is irrelevant here.
  int integer(int lo, int hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1u;
    return lo + static_cast<int>(engine_() % span);
  }

  // True with probability p.
  bool chance(double p) { return uniform() < p; }

  // Standard normal by Box-Muller (one of the pair is used, the stream stays simple).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1], log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

  std::uint64_t raw() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

// Mixes two numbers into one seed (SplitMix64 finaliser), e.g. a scene seed and a frame index.
inline std::uint64_t mixSeed(std::uint64_t a, std::uint64_t b) {
  std::uint64_t z = a + 0x9E3779B97F4A7C15ull * (b + 1u);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace uampc::world
