// The scan pattern of one frame: where each ray points and when it fires.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "uampc/lidar/lidar_model.hpp"

namespace uampc::raycaster {

struct PatternPoint {
  Eigen::Vector3f direction;  // unit vector in the LiDAR frame
  float time_offset = 0.0f;   // s since the frame start
  std::uint16_t ring = 0;     // ring (spinning) or laser (non-repetitive) index
};

// Points in one frame: points_per_second / frame_rate_hz, rounded (spinning: a whole number of
// columns).
std::size_t pointsPerFrame(const lidar::LidarModel& model);

// The pattern of frame number frame_index (0, 1, 2, ...). Non-repetitive patterns continue where
// frame_index - 1 ended, so their coverage builds up; spinning patterns ignore frame_index.
// Points come in firing order; time offsets lie in [0, 1 / frame_rate_hz).
std::vector<PatternPoint> scanPattern(const lidar::LidarModel& model, std::uint64_t frame_index);

// The same patterns frame after frame, keeping what does not change between frames: a zigzag
// head's azimuth is the same at the same point of every frame, so the sine and cosine of it are
// computed once (the trigonometry was most of a Mid-360 pattern's 0.7 ms), and so are each point's
// firing time and each laser's phase offset. Same points, bit for bit, as scanPattern.
class ScanPatternGenerator {
 public:
  explicit ScanPatternGenerator(lidar::LidarModel model);
  // Writes frame frame_index's pattern into `out` (resized; its memory is reused).
  void generate(std::uint64_t frame_index, std::vector<PatternPoint>& out) const;

 private:
  lidar::LidarModel model_;
  std::size_t points_;
  std::vector<double> cos_azimuth_, sin_azimuth_;  // zigzag: per point of a frame
  // Zigzag and rosette: each point's firing time in the frame, k / points_per_second (s), and each
  // laser's phase offset, laser / lasers: the same values every frame, so the two divisions per
  // point are done once (same operations, same bits).
  std::vector<double> times_, laser_phases_;
};

}  // namespace uampc::raycaster
