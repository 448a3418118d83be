#include "uampc/lo/local_map.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace uampc::lo {

namespace {

constexpr std::uint64_t kBias = std::uint64_t{1} << 20;  // 21 bits per axis: +-1M blocks
constexpr std::uint64_t kMask21 = (std::uint64_t{1} << 21) - 1;
constexpr std::size_t kInitialCapacity = 1 << 14;

// floor(v / 2); the right shift of a negative int is arithmetic on every compiler we target
// (and defined so from C++20).
int floorHalf(int v) { return v >> 1; }

// Index of a voxel inside its 2x2x2 block (two's complement: v & 1 is v mod 2).
int indexInBlock(const Voxel& v) { return (v.x() & 1) | ((v.y() & 1) << 1) | ((v.z() & 1) << 2); }

}  // namespace

LocalMap::LocalMap(double voxel_size, double max_radius)
    : voxel_size_(voxel_size), inverse_voxel_size_(1.0 / voxel_size), max_radius_(max_radius) {
  if (!(voxel_size > 0.0)) {
    throw std::invalid_argument("lo::LocalMap: voxel_size must be positive (m)");
  }
  rehash(kInitialCapacity);
}

std::uint64_t LocalMap::blockKey(const Voxel& v) {
  return ((static_cast<std::uint64_t>(floorHalf(v.x())) + kBias) & kMask21) |
         (((static_cast<std::uint64_t>(floorHalf(v.y())) + kBias) & kMask21) << 21) |
         (((static_cast<std::uint64_t>(floorHalf(v.z())) + kBias) & kMask21) << 42);
}

std::size_t LocalMap::home(std::uint64_t key) const {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
}

void LocalMap::clear() {
  keys_.clear();
  pool_.clear();
  times_.clear();
  free_.clear();
  size_ = 0;
  rehash(kInitialCapacity);
}

void LocalMap::rehash(std::size_t capacity) {
  std::vector<std::uint64_t> old_keys;
  std::vector<std::uint32_t> old_index;
  old_keys.swap(keys_);
  old_index.swap(index_);
  keys_.assign(capacity, kEmpty);
  index_.assign(capacity, 0);
  shift_ = 64;
  for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
  blocks_used_ = 0;
  erased_ = 0;
  for (std::size_t i = 0; i < old_keys.size(); ++i) {
    if (old_keys[i] < kErased) placeKey(old_keys[i], old_index[i]);
  }
}

std::size_t LocalMap::slotOf(std::uint64_t key) const {
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t i = home(key);; i = (i + 1) & mask) {
    if (keys_[i] == key) return i;
    if (keys_[i] == kEmpty) return kNoSlot;
  }
}

// Puts an absent key into the first free slot of its probe sequence.
void LocalMap::placeKey(std::uint64_t key, std::uint32_t block) {
  const std::size_t mask = keys_.size() - 1;
  std::size_t i = home(key);
  while (keys_[i] < kErased) i = (i + 1) & mask;
  if (keys_[i] == kErased) --erased_;
  keys_[i] = key;
  index_[i] = block;
  ++blocks_used_;
}

void LocalMap::insert(const std::vector<Eigen::Vector3d>& points_W, double time) {
  for (const auto& p : points_W) {
    const Voxel voxel = voxelOf(p, inverse_voxel_size_);
    const std::uint64_t key = blockKey(voxel);
    const std::size_t slot = slotOf(key);
    std::uint32_t b;
    if (slot != kNoSlot) {
      b = index_[slot];
    } else {
      // Keep the table at most half full (live blocks and tombstones), so probes stay short.
      if (2 * (blocks_used_ + erased_ + 1) > keys_.size()) {
        rehash(4 * (blocks_used_ + 1) > keys_.size() ? 2 * keys_.size() : keys_.size());
      }
      if (!free_.empty()) {
        b = free_.back();
        free_.pop_back();
      } else {
        b = static_cast<std::uint32_t>(pool_.size());
        pool_.emplace_back();
        times_.emplace_back();
      }
      pool_[b].occupied = 0;
      placeKey(key, b);
    }
    Block& block = pool_[b];
    const int index = indexInBlock(voxel);
    const auto bit = static_cast<std::uint8_t>(1u << index);
    if (!(block.occupied & bit)) {
      block.occupied |= bit;
      block.points_W[index] = p.cast<float>();
      ++size_;
    }
    times_[b][index] = time;  // the first point stays; when it was seen is refreshed
  }
}

void LocalMap::removeFarFrom(const Eigen::Vector3d& origin_W) {
  const Eigen::Vector3f origin = origin_W.cast<float>();
  const auto max_radius2 = static_cast<float>(max_radius_ * max_radius_);
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i] >= kErased) continue;
    Block& block = pool_[index_[i]];
    for (int j = 0; j < 8; ++j) {
      if ((block.occupied & (1u << j)) &&
          (block.points_W[j] - origin).squaredNorm() > max_radius2) {
        block.occupied = static_cast<std::uint8_t>(block.occupied & ~(1u << j));
        --size_;
      }
    }
    if (block.occupied == 0) {
      keys_[i] = kErased;
      free_.push_back(index_[i]);
      --blocks_used_;
      ++erased_;
    }
  }
}

std::size_t LocalMap::nearest(const Eigen::Vector3d& q, std::size_t k,
                              std::vector<Eigen::Vector3d>& neighbours) const {
  neighbours.clear();
  if (k == 0) return 0;
  // The k best so far, sorted by squared distance (k is small: insertion beats sorting).
  constexpr std::size_t kMaxK = 16;
  std::array<std::pair<float, const Eigen::Vector3f*>, kMaxK> best;
  k = std::min(k, kMaxK);
  std::size_t n = 0;
  const Eigen::Vector3f qf = q.cast<float>();
  const Voxel center = voxelOf(q, inverse_voxel_size_);
  // Voxels center-1 .. center+1 span exactly two blocks along each axis. The 8 look-ups are
  // independent: their keys, then their blocks, are prefetched together so that the cache
  // misses overlap instead of queueing one behind the other.
  const Voxel low = center - Voxel::Ones();
  std::array<std::uint64_t, 8> keys;
  for (int c = 0; c < 8; ++c) {
    keys[c] = blockKey(Voxel(low.x() + 2 * (c & 1), low.y() + (c & 2), low.z() + ((c & 4) >> 1)));
    __builtin_prefetch(&keys_[home(keys[c])]);
  }
  std::array<const Block*, 8> blocks;
  std::size_t found = 0;
  for (int c = 0; c < 8; ++c) {
    const std::size_t slot = slotOf(keys[c]);
    if (slot == kNoSlot) continue;
    blocks[found] = &pool_[index_[slot]];
    __builtin_prefetch(blocks[found]);
    __builtin_prefetch(reinterpret_cast<const char*>(blocks[found]) + 64);
    ++found;
  }
  for (std::size_t c = 0; c < found; ++c) {
    const Block& block = *blocks[c];
    for (unsigned bits = block.occupied; bits != 0; bits &= bits - 1) {
      const int j = __builtin_ctz(bits);
      const float d2 = (block.points_W[j] - qf).squaredNorm();
      if (n == k && d2 >= best[k - 1].first) continue;
      std::size_t i = (n < k) ? n++ : k - 1;
      while (i > 0 && best[i - 1].first > d2) {
        best[i] = best[i - 1];
        --i;
      }
      best[i] = {d2, &block.points_W[j]};
    }
  }
  for (std::size_t i = 0; i < n; ++i) neighbours.push_back(best[i].second->cast<double>());
  return n;
}

std::vector<MapPoint> LocalMap::points(double observed_since) const {
  std::vector<MapPoint> out;
  out.reserve(size_);
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i] >= kErased) continue;
    const Block& block = pool_[index_[i]];
    const auto& times = times_[index_[i]];
    for (int j = 0; j < 8; ++j) {
      if ((block.occupied & (1u << j)) && times[j] >= observed_since) {
        out.push_back({block.points_W[j].cast<double>(), times[j]});
      }
    }
  }
  return out;
}

}  // namespace uampc::lo
