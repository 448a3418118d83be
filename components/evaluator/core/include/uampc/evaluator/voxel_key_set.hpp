// A set of 64-bit voxel keys: open addressing, linear probing, no erase.
//
// CMPLT inserts every point of every scan (200k points/s, twice: estimate and ground truth);
// std::unordered_set allocates a node per voxel and costs a cache miss or two per look-up, this
// flat table about one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace uampc::evaluator {

class VoxelKeySet {
 public:
  // kEmpty (all ones) cannot be stored; Completeness keys use 63 bits.
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  // True when key was not in the set yet.
  bool insert(std::uint64_t key) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (std::size_t slot = home(key);; slot = (slot + 1) & (slots_.size() - 1)) {
      if (slots_[slot] == key) return false;
      if (slots_[slot] == kEmpty) {
        slots_[slot] = key;
        ++size_;
        return true;
      }
    }
  }

  std::size_t size() const { return size_; }

  template <typename Function>
  void forEach(Function function) const {
    for (const std::uint64_t key : slots_) {
      if (key != kEmpty) function(key);
    }
  }

 private:
  std::size_t home(std::uint64_t key) const {
    key ^= key >> 29;
    key *= 0xBF58476D1CE4E5B9ull;  // splitmix64's mixer; the top bits index the table
    return static_cast<std::size_t>(key >> shift_);
  }

  void grow() {
    std::vector<std::uint64_t> old(slots_.size() ? 2 * slots_.size() : 1024, kEmpty);
    old.swap(slots_);
    shift_ = 64;
    for (std::size_t n = slots_.size(); n > 1; n >>= 1) --shift_;
    size_ = 0;
    for (const std::uint64_t key : old) {
      if (key != kEmpty) insert(key);
    }
  }

  std::vector<std::uint64_t> slots_;  // capacity a power of two, at most half full
  std::size_t size_ = 0;
  int shift_ = 64;  // 64 - log2(capacity)
};

}  // namespace uampc::evaluator
