#include "uampc/lo/local_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

LocalMap::LocalMap(double voxel_size, double max_radius, int mean_points)
    : voxel_size_(voxel_size),
      inverse_voxel_size_(1.0 / voxel_size),
      max_radius_(max_radius),
      mean_points_(static_cast<std::uint8_t>(std::clamp(mean_points, 1, 255))) {
  if (!(voxel_size > 0.0)) {
    throw std::invalid_argument("lo::LocalMap: voxel_size must be positive (m)");
  }
  if (mean_points < 1 || mean_points > 255) {
    throw std::invalid_argument("lo::LocalMap: mean_points must be within 1 and 255");
  }
  rehash(kInitialCapacity);
}

std::uint64_t LocalMap::blockKey(const Voxel& v) {
  return ((static_cast<std::uint64_t>(floorHalf(v.x())) + kBias) & kMask21) |
         (((static_cast<std::uint64_t>(floorHalf(v.y())) + kBias) & kMask21) << 21) |
         (((static_cast<std::uint64_t>(floorHalf(v.z())) + kBias) & kMask21) << 42);
}

void LocalMap::clear() {
  slots_.clear();
  pool_.clear();
  times_.clear();
  latest_.clear();
  counts_.clear();
  free_.clear();
  size_ = 0;
  rehash(kInitialCapacity);
}

void LocalMap::rehash(std::size_t capacity) {
  std::vector<Slot> old;
  old.swap(slots_);
  slots_.assign(capacity, Slot{kEmpty, 0});
  shift_ = 64;
  for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
  blocks_used_ = 0;
  erased_ = 0;
  for (const Slot& slot : old) {
    if (slot.key < kErased) placeKey(slot.key, slot.block);
  }
}

// Puts an absent key into the first free slot of its probe sequence.
void LocalMap::placeKey(std::uint64_t key, std::uint32_t block) {
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = home(key);
  while (slots_[i].key < kErased) i = (i + 1) & mask;
  if (slots_[i].key == kErased) --erased_;
  slots_[i] = Slot{key, block};
  ++blocks_used_;
}

void LocalMap::insert(const std::vector<Eigen::Vector3d>& points_W, double time, const Eigen::Vector3d& viewpoint_W) {
  // Successive points of a scan often fall in the same block: remember the last one.
  std::uint64_t last_key = kEmpty;
  std::uint32_t b = 0;
  for (const auto& p : points_W) {
    const Voxel voxel = voxelOf(p, inverse_voxel_size_);
    const std::uint64_t key = blockKey(voxel);
    if (key != last_key) {
      const std::size_t slot = slotOf(key);
      if (slot != kNoSlot) {
        b = slots_[slot].block;
      } else {
        // Keep the table at most half full (live blocks and tombstones), so probes stay short.
        if (2 * (blocks_used_ + erased_ + 1) > slots_.size()) {
          rehash(4 * (blocks_used_ + 1) > slots_.size() ? 2 * slots_.size() : slots_.size());
        }
        if (!free_.empty()) {
          b = free_.back();
          free_.pop_back();
        } else {
          b = static_cast<std::uint32_t>(pool_.size());
          pool_.emplace_back();
          times_.emplace_back();
          latest_.emplace_back(time);
          counts_.emplace_back();
        }
        pool_[b].occupied = 0;
        placeKey(key, b);
      }
      last_key = key;
    }
    Block& block = pool_[b];
    const int index = indexInBlock(voxel);
    const auto bit = static_cast<std::uint8_t>(1u << index);
    if (!(block.occupied & bit)) {
      block.occupied |= bit;
      block.x[index] = static_cast<float>(p.x());
      block.y[index] = static_cast<float>(p.y());
      block.z[index] = static_cast<float>(p.z());
      // A point at the viewpoint itself (never, past the LO's minimum range) gets no view: it
      // then votes for neither side.
      const Eigen::Vector3d view = (viewpoint_W - p).stableNormalized() * 127.0;
      for (int a = 0; a < 3; ++a) block.views[index][a] = static_cast<std::int8_t>(std::lround(view[a]));
      counts_[b][index] = 1;
      ++size_;
    } else if (counts_[b][index] < mean_points_) {
      // The running mean of the voxel's first mean_points_ observations (the view stays the
      // first one's: it only tells which side of a surface was seen).
      const float count = static_cast<float>(++counts_[b][index]);
      block.x[index] += (static_cast<float>(p.x()) - block.x[index]) / count;
      block.y[index] += (static_cast<float>(p.y()) - block.y[index]) / count;
      block.z[index] += (static_cast<float>(p.z()) - block.z[index]) / count;
    }
    times_[b][index] = time;  // when it was seen is refreshed
    latest_[b] = std::max(latest_[b], time);
  }
}

void LocalMap::removeFarFrom(const Eigen::Vector3d& origin_W) {
  const Eigen::Vector3f origin = origin_W.cast<float>();
  const auto max_radius2 = static_cast<float>(max_radius_ * max_radius_);
  // A block whose whole box (with a millimetre for float rounding) lies within the radius keeps
  // all its points without looking at them: only the thin shell at the radius is tested point by
  // point, and the blocks inside are never touched, just their keys.
  const double block_size = 2.0 * voxel_size_;
  const double inner = std::max(0.0, max_radius_ - 1e-3);
  for (Slot& slot : slots_) {
    if (slot.key >= kErased) continue;
    double far2 = 0.0;  // squared distance from origin to the farthest corner of the block
    for (int axis = 0; axis < 3; ++axis) {
      const auto cell = static_cast<std::int64_t>((slot.key >> (21 * axis)) & kMask21) -
                        static_cast<std::int64_t>(kBias);
      const double low = static_cast<double>(cell) * block_size - origin_W[axis];
      const double far = std::max(std::abs(low), std::abs(low + block_size));
      far2 += far * far;
    }
    if (far2 < inner * inner) continue;
    Block& block = pool_[slot.block];
    for (int j = 0; j < 8; ++j) {
      if ((block.occupied & (1u << j)) && (block.point(j) - origin).squaredNorm() > max_radius2) {
        block.occupied = static_cast<std::uint8_t>(block.occupied & ~(1u << j));
        --size_;
      }
    }
    if (block.occupied == 0) {
      slot.key = kErased;
      free_.push_back(slot.block);
      --blocks_used_;
      ++erased_;
    }
  }
}

namespace {

// The k best candidates so far, sorted by squared distance (k is small: insertion beats sorting).
// Block and View are LocalMap's, passed in so that this step stays a plain type of this file.
template <class Block, class View>
class KNearest {
 public:
  static constexpr std::size_t kMaxK = 16;
  explicit KNearest(std::size_t k) : k_(std::min(k, kMaxK)) {}

  // Squared distance of the k-th best so far: a block farther than this holds nothing better.
  float worst() const { return worst_; }

  // The block's points nearer than the k-th best go through the insertion. The 8 squared distances
  // are computed together (SIMD); after the first block or two, only a few of the ~20 candidates
  // pass, and the test itself does not branch.
  void offer(const Block& block, const Eigen::Vector3f& q) {
    using Array8f = Eigen::Array<float, 8, 1>;
    const Array8f d2 = (Eigen::Map<const Array8f>(block.x.data()) - q.x()).square() +
                       (Eigen::Map<const Array8f>(block.y.data()) - q.y()).square() +
                       (Eigen::Map<const Array8f>(block.z.data()) - q.z()).square();
    unsigned nearer = 0;
    for (int j = 0; j < 8; ++j) nearer |= static_cast<unsigned>(d2[j] < worst_) << j;
    for (unsigned bits = nearer & block.occupied; bits != 0; bits &= bits - 1) {
      const int j = __builtin_ctz(bits);
      if (d2[j] >= worst_) continue;  // worst shrank since
      insert({d2[j], block.point(j), &block.views[j]});
    }
  }

  std::size_t copyOut(std::vector<Eigen::Vector3d>& neighbours, std::vector<Eigen::Vector3f>* views) const {
    for (std::size_t i = 0; i < n_; ++i) neighbours.push_back(best_[i].point.template cast<double>());
    if (views != nullptr) {
      for (std::size_t i = 0; i < n_; ++i) {
        const View& v = *best_[i].view;
        views->push_back(Eigen::Vector3f(v[0], v[1], v[2]) / 127.0f);
      }
    }
    return n_;
  }

 private:
  struct Candidate {
    float d2;
    Eigen::Vector3f point;
    const View* view;
  };
  void insert(const Candidate& c) {
    std::size_t i = (n_ < k_) ? n_++ : k_ - 1;
    while (i > 0 && best_[i - 1].d2 > c.d2) {
      best_[i] = best_[i - 1];
      --i;
    }
    best_[i] = c;
    if (n_ == k_) worst_ = best_[k_ - 1].d2;
  }

  std::size_t k_;
  std::size_t n_ = 0;
  float worst_ = std::numeric_limits<float>::infinity();
  std::array<Candidate, kMaxK> best_;
};

}  // namespace

// Voxels center-1 .. center+1 span exactly two blocks along each axis, one of which holds q. A
// block's squared distance to q (0 for q's own block) bounds its points' from below, so a block is
// skipped once k points nearer than it are known: the same k points as an exhaustive search of the
// 8 blocks. Visiting them roughly nearest first (q's block, then across the nearest faces) makes
// the skips frequent. The bound is loosened by 1 mm so that float rounding of the stored points
// cannot skip one the search would take.
LocalMap::NearbyBlocks LocalMap::nearbyBlocks(const Eigen::Vector3d& q) const {
  const Voxel center = voxelOf(q, inverse_voxel_size_);
  const double block_size = 2.0 * voxel_size_;
  // Per axis, the key bits and the squared distance from q of q's own block (0) and of the other
  // one. Whether the other lies below or above is the parity of q's voxel; the distances of the
  // 8 blocks are then sums of table entries, not branches on data (mispredicted ones cost more
  // than the rest of a block's work).
  std::array<std::array<std::uint64_t, 2>, 3> key_part;  // [axis][own, other]
  std::array<std::array<float, 2>, 3> gap2;              // [axis][own, other], m^2
  for (int a = 0; a < 3; ++a) {
    const int own = floorHalf(center[a]);
    const int upper_voxel = center[a] & 1;  // q's voxel is the upper one of its block
    const int other = own - 1 + 2 * upper_voxel;
    const double split = (own + upper_voxel) * block_size;  // face between the two blocks
    const double gap = std::max(0.0, std::abs(q[a] - split) - 1e-3);
    gap2[a] = {0.0f, static_cast<float>(gap * gap)};
    key_part[a] = {((static_cast<std::uint64_t>(own) + kBias) & kMask21) << (21 * a),
                   ((static_cast<std::uint64_t>(other) + kBias) & kMask21) << (21 * a)};
  }
  // Axes by increasing gap (three compare-exchanges).
  std::array<int, 3> axis = {0, 1, 2};
  if (gap2[axis[1]][1] < gap2[axis[0]][1]) std::swap(axis[0], axis[1]);
  if (gap2[axis[2]][1] < gap2[axis[1]][1]) std::swap(axis[1], axis[2]);
  if (gap2[axis[1]][1] < gap2[axis[0]][1]) std::swap(axis[0], axis[1]);
  const int a0 = 1 << axis[0], a1 = 1 << axis[1], a2 = 1 << axis[2];
  // Which axes each visited block lies across from q's block, roughly nearest first.
  const std::array<int, 8> across = {0, a0, a1, a2, a0 | a1, a0 | a2, a1 | a2, 7};
  NearbyBlocks nearby;
  for (int c = 0; c < 8; ++c) {
    const int x = across[c] & 1, y = (across[c] >> 1) & 1, z = across[c] >> 2;
    nearby.keys[c] = key_part[0][x] | key_part[1][y] | key_part[2][z];
    nearby.box2[c] = gap2[0][x] + gap2[1][y] + gap2[2][z];
    __builtin_prefetch(&slots_[home(nearby.keys[c])]);
  }
  return nearby;
}

// All 8 blocks are looked up before any is searched, so that their cache misses overlap instead
// of following one another; the search skips blocks, not look-ups.
std::array<const LocalMap::Block*, 8> LocalMap::lookUp(const NearbyBlocks& nearby) const {
  std::array<const Block*, 8> blocks;
  for (int c = 0; c < 8; ++c) {
    const std::size_t slot = slotOf(nearby.keys[c]);
    blocks[c] = slot == kNoSlot ? nullptr : &pool_[slots_[slot].block];
    if (blocks[c] != nullptr) {
      __builtin_prefetch(blocks[c]);
      __builtin_prefetch(reinterpret_cast<const char*>(blocks[c]) + sizeof(Block) - 1);
    }
  }
  return blocks;
}

std::size_t LocalMap::nearest(const Eigen::Vector3d& q, std::size_t k, std::vector<Eigen::Vector3d>& neighbours,
                              std::vector<Eigen::Vector3f>* views) const {
  neighbours.clear();
  if (views != nullptr) views->clear();
  if (k == 0) return 0;
  const NearbyBlocks nearby = nearbyBlocks(q);
  return searchBlocks(q, nearby, lookUp(nearby), k, neighbours, views);
}

std::size_t LocalMap::searchBlocks(const Eigen::Vector3d& q, const NearbyBlocks& nearby,
                                   const std::array<const Block*, 8>& blocks, std::size_t k,
                                   std::vector<Eigen::Vector3d>& neighbours, std::vector<Eigen::Vector3f>* views) const {
  neighbours.clear();
  if (views != nullptr) views->clear();
  if (k == 0) return 0;
  KNearest<Block, View> best(k);
  const Eigen::Vector3f qf = q.cast<float>();
  for (int c = 0; c < 8; ++c) {
    if (nearby.box2[c] > best.worst() || blocks[c] == nullptr) continue;
    best.offer(*blocks[c], qf);
  }
  return best.copyOut(neighbours, views);
}

LocalMap::Search::Search(const LocalMap& map, const std::vector<Eigen::Vector3d>& queries)
    : map_(map), queries_(queries) {
  for (std::size_t i = 0; i < kSlotsAhead && i < queries_.size(); ++i) fetchSlots(i);
  for (std::size_t i = 0; i < kBlocksAhead && i < queries_.size(); ++i) fetchBlocks(i);
}

void LocalMap::Search::fetchSlots(std::size_t i) { ring_[i % kRing].nearby = map_.nearbyBlocks(queries_[i]); }

void LocalMap::Search::fetchBlocks(std::size_t i) {
  Stage& stage = ring_[i % kRing];
  stage.blocks = map_.lookUp(stage.nearby);
}

std::size_t LocalMap::Search::next(std::size_t k, std::vector<Eigen::Vector3d>& neighbours,
                                   std::vector<Eigen::Vector3f>* views) {
  const std::size_t i = next_++;
  if (i + kSlotsAhead < queries_.size()) fetchSlots(i + kSlotsAhead);
  if (i + kBlocksAhead < queries_.size()) fetchBlocks(i + kBlocksAhead);
  const Stage& stage = ring_[i % kRing];
  return map_.searchBlocks(queries_[i], stage.nearby, stage.blocks, k, neighbours, views);
}

// The block pool is walked in memory order: freed blocks hold no occupied voxel, so they add
// nothing, and the hash table's random order would cost a cache miss per block.
template <class Visit>
void LocalMap::forEachPointSince(double observed_since, Visit&& visit) const {
  for (std::size_t b = 0; b < pool_.size(); ++b) {
    if (latest_[b] < observed_since) continue;
    const Block& block = pool_[b];
    for (int j = 0; j < 8; ++j) {
      if ((block.occupied & (1u << j)) && times_[b][j] >= observed_since) visit(block.point(j), times_[b][j]);
    }
  }
}

std::vector<MapPoint> LocalMap::points(double observed_since) const {
  std::vector<MapPoint> out;
  out.reserve(size_);
  forEachPointSince(observed_since,
                    [&out](const Eigen::Vector3f& p, double time) { out.push_back({p.cast<double>(), time}); });
  return out;
}

void LocalMap::pointsSince(double observed_since, std::vector<Eigen::Vector3f>& out) const {
  out.clear();
  forEachPointSince(observed_since, [&out](const Eigen::Vector3f& p, double) { out.push_back(p); });
}

}  // namespace uampc::lo
