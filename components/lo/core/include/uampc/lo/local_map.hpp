// The LO's local map: a voxel hash map holding one world point per voxel.
//
// Voxel downsampling of the map (0.3 m by default) is the voxel grid itself: a voxel holds one
// point, the mean of the first mean_points points seen in it (1: the first point stays); later
// ones only refresh the voxel's observation time. Averaging takes the sensor's noise out of the
// map that every later scan is matched against (docs/results/lo-degenerate-geometry.md, "The map's
// points"). The map is bounded: voxels farther than max_radius from the sensor are dropped, so its
// size does not grow with the length of the run.
//
// Neighbour search is the hottest loop of the odometry. Voxels are stored by 2x2x2 blocks in an
// open-addressing hash table (linear probing, tombstones on erase), so the 3x3x3 voxels around
// a query are covered by 8 block look-ups instead of 27 voxel look-ups. The blocks are visited
// nearest first and skipped once they cannot hold anything nearer than the k-th best point, and
// a block keeps its points as coordinate arrays so its 8 distances are computed together.
//
// Each voxel also keeps the direction from its point towards the sensor that first saw it (the
// side of the surface that was seen): a scan point seen from the other side of a thin slab or wall
// must not be matched to the face that the map holds (see IteratedEkf::update).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "uampc/lo/voxel.hpp"

namespace uampc::lo {

struct MapPoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double time = 0.0;  // s, when the voxel was last observed
};

class LocalMap {
 public:
  // mean_points: how many observations a voxel's point averages (at least 1, at most 255).
  LocalMap(double voxel_size, double max_radius, int mean_points = 1);

  // Adds world points observed at time (s) by a sensor at viewpoint_W.
  void insert(const std::vector<Eigen::Vector3d>& points_W, double time, const Eigen::Vector3d& viewpoint_W);

  // Drops voxels whose point is farther than max_radius from origin_W.
  void removeFarFrom(const Eigen::Vector3d& origin_W);

  // Up to k map points nearest to q, nearest first, written to neighbours (cleared first); the
  // candidates are the points of the 8 blocks covering the 3x3x3 voxels around q's voxel (at
  // least 1 voxel of margin in every direction). Returns how many were found. With views, also
  // writes each neighbour's unit direction towards the sensor that saw it, in the same order.
  std::size_t nearest(const Eigen::Vector3d& q, std::size_t k, std::vector<Eigen::Vector3d>& neighbours,
                      std::vector<Eigen::Vector3f>* views = nullptr) const;

  // nearest() of many queries in turn, with the same results. A search waits on memory: it reads
  // 8 table slots, then the 8 blocks they point to. Here the slots of the query kSlotsAhead places
  // on and the blocks of the one kBlocksAhead on are fetched while the current one is searched, so
  // the cache misses of successive queries overlap instead of following one another.
  class Search;


  // Points observed at or after observed_since (s); all points by default.
  std::vector<MapPoint> points(
      double observed_since = -std::numeric_limits<double>::infinity()) const;
  // The same points' coordinates only, into out (cleared first; its capacity is reused): what
  // the LO publishes as its local map every frame.
  void pointsSince(double observed_since, std::vector<Eigen::Vector3f>& out) const;

  std::size_t size() const { return size_; }
  // Heap memory held by the map (table and block pool), bytes.
  std::size_t memoryBytes() const {
    return slots_.capacity() * sizeof(Slot) + pool_.capacity() * sizeof(Block) +
           times_.capacity() * sizeof(times_[0]) + latest_.capacity() * sizeof(double) +
           counts_.capacity() * sizeof(counts_[0]) +
           free_.capacity() * sizeof(std::uint32_t);
  }
  bool empty() const { return size_ == 0; }
  void clear();
  double voxelSize() const { return voxel_size_; }
  double maxRadius() const { return max_radius_; }

 private:
  double voxel_size_;
  double inverse_voxel_size_;
  double max_radius_;
  std::uint8_t mean_points_;

  // Unit direction from a point towards the sensor that first saw it, times 127 (a sign test
  // needs no more).
  using View = std::array<std::int8_t, 3>;
  // Eight voxels, 2x2x2; bit i of occupied says whether voxel i holds a point. Points are
  // float (plenty for 0.3 m voxels within a few km of the origin) and stored as x, y and z
  // arrays, so that the squared distances of all 8 to a query vectorise. With the views, a block
  // is 121 bytes, aligned to exactly two cache lines: a search prefetches both and then finds
  // everything it reads of the block there (views kept apart cost a cache miss per neighbour's
  // block: 7 % of the search).
  struct alignas(64) Block {
    std::array<float, 8> x, y, z;
    std::array<View, 8> views;
    std::uint8_t occupied = 0;
    Eigen::Vector3f point(int i) const { return {x[i], y[i], z[i]}; }
  };
  static_assert(sizeof(Block) == 128, "a block is two cache lines");
  // A table slot: the block key and the block's pool index side by side, so that a look-up
  // touches one cache line.
  struct Slot {
    std::uint64_t key;
    std::uint32_t block;
  };
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  static constexpr std::uint64_t kErased = kEmpty - 1;
  static constexpr std::size_t kNoSlot = ~std::size_t{0};
  static std::uint64_t blockKey(const Voxel& voxel);
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);  // Fibonacci
  }
  std::size_t slotOf(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = home(key);; i = (i + 1) & mask) {
      if (slots_[i].key == key) return i;
      if (slots_[i].key == kEmpty) return kNoSlot;
    }
  }
  void placeKey(std::uint64_t key, std::uint32_t block);
  // nearest(), in its steps: the 8 blocks around q and a lower bound for each one's points'
  // squared distance to q, then the blocks themselves (nullptr where none is stored).
  struct NearbyBlocks {
    std::array<std::uint64_t, 8> keys;
    std::array<float, 8> box2;  // m^2
  };
  NearbyBlocks nearbyBlocks(const Eigen::Vector3d& q) const;
  std::array<const Block*, 8> lookUp(const NearbyBlocks& nearby) const;
  std::size_t searchBlocks(const Eigen::Vector3d& q, const NearbyBlocks& nearby,
                           const std::array<const Block*, 8>& blocks, std::size_t k,
                           std::vector<Eigen::Vector3d>& neighbours, std::vector<Eigen::Vector3f>* views) const;
  // visit(point, observation time) for every occupied voxel observed at or after observed_since.
  template <class Visit>
  void forEachPointSince(double observed_since, Visit&& visit) const;
  void rehash(std::size_t capacity);

  // Open-addressing table from block key to an index into the dense block pool.
  std::vector<Slot> slots_;  // capacity a power of two; key kEmpty, kErased or a block key
  std::vector<Block> pool_;  // blocks, dense
  std::vector<std::array<double, 8>> times_;  // observation times, parallel to pool_
  // The latest of a block's observation times, parallel to pool_: the LO publishes the points of
  // the last seconds every frame, and most blocks of the map are older; this skips them without
  // touching their 128 bytes (or their 64 of times).
  std::vector<double> latest_;
  // How many observations each voxel's point averages so far, parallel to pool_ (only grows to
  // mean_points_).
  std::vector<std::array<std::uint8_t, 8>> counts_;
  std::vector<std::uint32_t> free_;           // pool indices of removed blocks, for reuse
  std::size_t size_ = 0;                      // occupied voxels
  std::size_t blocks_used_ = 0;               // live blocks
  std::size_t erased_ = 0;                    // tombstones
  int shift_ = 64;                            // 64 - log2(capacity), for Fibonacci hashing
};

class LocalMap::Search {
 public:
  // queries must outlive the search, and the map must not change during it.
  Search(const LocalMap& map, const std::vector<Eigen::Vector3d>& queries);
  // The neighbours of the next query, as nearest() gives them (at most queries.size() calls).
  std::size_t next(std::size_t k, std::vector<Eigen::Vector3d>& neighbours,
                   std::vector<Eigen::Vector3f>* views = nullptr);

 private:
  static constexpr std::size_t kSlotsAhead = 6;
  static constexpr std::size_t kBlocksAhead = 3;
  static constexpr std::size_t kRing = 8;  // a power of two above kSlotsAhead
  struct Stage {
    NearbyBlocks nearby;
    std::array<const Block*, 8> blocks;
  };
  void fetchSlots(std::size_t i);
  void fetchBlocks(std::size_t i);
  const LocalMap& map_;
  const std::vector<Eigen::Vector3d>& queries_;
  std::array<Stage, kRing> ring_;
  std::size_t next_ = 0;
};

}  // namespace uampc::lo
