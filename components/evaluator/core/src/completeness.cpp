#include "uampc/evaluator/completeness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "uampc/evaluator/voxel_octree.hpp"

namespace uampc::evaluator {

namespace {

constexpr int kKeyBits = 21;
constexpr double kKeyOffset = 1 << (kKeyBits - 1);  // 2^20 voxels each way
constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;

// floor((coordinate - grid_offset) / voxel_size) shifted to [0, 2^21); false when out of range.
bool keyComponent(float coordinate, double grid_offset, double inverse_voxel_size, std::uint64_t& component) {
  const double shifted =
      std::floor((static_cast<double>(coordinate) - grid_offset) * inverse_voxel_size) + kKeyOffset;
  if (!(shifted >= 0.0) || !(shifted < 2.0 * kKeyOffset)) return false;
  component = static_cast<std::uint64_t>(shifted);
  return true;
}

int unpack(std::uint64_t key, int shift) {
  return static_cast<int>((key >> shift) & kKeyMask) - static_cast<int>(kKeyOffset);
}

}  // namespace

Completeness::Completeness(CompletenessConfig config)
    : config_(config), inverse_voxel_size_(1.0 / config.voxel_size) {
  if (!(config_.voxel_size > 0.0) || !std::isfinite(config_.voxel_size)) {
    throw std::invalid_argument("Completeness: voxel_size must be > 0 m, got " +
                                std::to_string(config_.voxel_size));
  }
  if (!std::isfinite(config_.grid_offset)) {
    throw std::invalid_argument("Completeness: grid_offset must be finite (m)");
  }
  if (!(config_.window_duration > 0.0) || !std::isfinite(config_.window_duration)) {
    throw std::invalid_argument("Completeness: window_duration must be > 0 s, got " +
                                std::to_string(config_.window_duration));
  }
}

Completeness::VoxelSet* Completeness::openSetFor(long index) {
  if (index > current_.index) {
    if (index == current_.index + 1) {
      previous_ = std::move(current_);
    } else {
      previous_ = OpenWindow{index - 1, {}};  // it had no scan: its set is empty
    }
    current_ = OpenWindow{index, {}};
  }
  if (index == current_.index) return &current_.voxels;
  if (index == previous_.index) return &previous_.voxels;
  return nullptr;
}

void Completeness::addScan(double stamp, const std::vector<Eigen::Vector3f>& points_world) {
  if (!std::isfinite(stamp)) {
    ++invalid_scans_;
    return;
  }
  if (!started_) {
    started_ = true;
    t0_ = stamp;
    current_ = OpenWindow{0, {}};
    previous_ = OpenWindow{-1, {}};
  }
  ++scans_;
  latest_stamp_ = std::max(latest_stamp_, stamp);
  const long index = static_cast<long>(std::floor((stamp - t0_) / config_.window_duration));
  VoxelSet* window = index >= 0 ? openSetFor(index) : nullptr;
  if (window == nullptr) ++late_scans_;

  std::size_t valid = 0;
  for (const Eigen::Vector3f& p : points_world) {
    if (!p.allFinite()) {
      ++invalid_points_;
      continue;
    }
    std::uint64_t x = 0, y = 0, z = 0;
    const double o = config_.grid_offset;
    if (!keyComponent(p.x(), o, inverse_voxel_size_, x) || !keyComponent(p.y(), o, inverse_voxel_size_, y) ||
        !keyComponent(p.z(), o, inverse_voxel_size_, z)) {
      ++out_of_range_points_;
      continue;
    }
    ++valid;
    const Key key = (x << (2 * kKeyBits)) | (y << kKeyBits) | z;
    // A voxel already in the window's set is already in the total: one look-up for most points.
    if (window == nullptr || window->insert(key)) total_.insert(key);
  }
  points_ += valid;

  if (window != nullptr) {
    CompletenessWindow& stats = windows_[index];
    stats.index = index;
    stats.start = t0_ + static_cast<double>(index) * config_.window_duration;
    stats.end = t0_ + static_cast<double>(index + 1) * config_.window_duration;
    stats.voxels = window->size();
    stats.scans += 1;
    stats.points += valid;
  }
}

CompletenessReport Completeness::report() const { return report(latest_stamp_); }

CompletenessReport Completeness::report(double end_time) const {
  CompletenessReport report;
  report.total_voxels = total_.size();
  report.scans = scans_;
  report.points = points_;
  report.invalid_points = invalid_points_;
  report.out_of_range_points = out_of_range_points_;
  report.late_scans = late_scans_;
  report.invalid_scans = invalid_scans_;
  if (!started_) return report;

  // Same floor as the window of a stamp: a window is complete once end_time lies past it.
  const double end_index = std::floor((end_time - t0_) / config_.window_duration);
  double sum = 0.0;
  for (const auto& [index, window] : windows_) {
    CompletenessWindow w = window;
    w.complete = static_cast<double>(index) < end_index;
    if (w.complete) {
      sum += static_cast<double>(w.voxels);
      ++report.complete_windows;
    }
    report.windows.push_back(w);
  }
  if (report.complete_windows > 0) {
    report.mean_voxels_per_window = sum / static_cast<double>(report.complete_windows);
  }
  return report;
}

std::vector<Eigen::Vector3i> Completeness::voxels() const {
  std::vector<Eigen::Vector3i> voxels;
  voxels.reserve(total_.size());
  total_.forEach([&voxels](Key key) {
    voxels.emplace_back(unpack(key, 2 * kKeyBits), unpack(key, kKeyBits), unpack(key, 0));
  });
  return voxels;
}

std::size_t Completeness::saveOctree(const std::string& path) const {
  return writeVoxelOctree(path, voxels(), config_.voxel_size);
}

}  // namespace uampc::evaluator
