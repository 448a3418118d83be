#include "uampc/mpc/depth_map_normals.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace uampc::mpc {

DepthMapNormals::DepthMapNormals() : DepthMapNormals(Config{}) {}

DepthMapNormals::DepthMapNormals(const Config& config) : config_(config) {}

void DepthMapNormals::reset(const PanoramicDepthMap& map) {
  map_ = &map;
  const std::size_t pixels = static_cast<std::size_t>(map.width()) * map.height();
  ++generation_;
  if (cache_.size() != pixels || generation_ == 0) {
    // Generation 0 marks never-used entries; the first reset after a wrap starts again at 1.
    cache_.assign(pixels, CachedNormal{Eigen::Vector3f::Zero(), kUnknown, 0});
    generation_ = 1;
  }
  computed_count_ = 0;
}

void DepthMapNormals::throwNotReset() {
  throw std::logic_error("DepthMapNormals::normal called before reset");
}

DepthMapNormals::State DepthMapNormals::compute(std::int32_t centre_pixel, Eigen::Vector3f* normal) {
  ++computed_count_;
  return estimate(*map_, centre_pixel, normal) ? kValid : kInvalid;
}

bool DepthMapNormals::estimate(const PanoramicDepthMap& map, std::int32_t centre_pixel,
                               Eigen::Vector3f* normal_B) const {
  // The ring is walked from the point's own pixel, whatever pixel asked: a point's normal is then
  // one value however the rays reach it, so U's rays may resolve pixels in any order (and the
  // ring is centred on the point, not on the edge of its splat).
  if (centre_pixel < 0) return false;
  const int width = map.width();
  const int height = map.height();
  const int u = centre_pixel % width;
  const int v = centre_pixel / width;
  const Eigen::Vector3f& centre = map.centrePoint(centre_pixel);
  const float range = centre.norm();
  const float max_jump = static_cast<float>(config_.max_range_jump_ratio) * range;

  // The 8 ring directions in angular order around the point's pixel.
  static constexpr int kDu[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  static constexpr int kDv[8] = {0, -1, -1, -1, 0, 1, 1, 1};
  Eigen::Vector3f offsets[8];
  int ring_position[8];
  int found = 0;
  for (int k = 0; k < 8; ++k) {
    // Rows clamp: the walk ends at the zenith or nadir row.
    const int rows_left =
        kDv[k] < 0 ? v : (kDv[k] > 0 ? height - 1 - v : config_.neighbour_reach_px);
    const int reach = std::min(config_.neighbour_reach_px, rows_left);
    int uu = u;
    int q = centre_pixel;
    for (int step = 1; step <= reach; ++step) {
      // Columns wrap; stepping by one pixel needs no integer division (which cost most of the
      // time here when written as a modulo).
      uu += kDu[k];
      q += kDv[k] * width + kDu[k];
      if (uu < 0) {
        uu += width;
        q += width;
      } else if (uu >= width) {
        uu -= width;
        q -= width;
      }
      // A hole, or the centre point's own splat: look one pixel further.
      if (!map.occupied(q) || map.centrePixel(q) == centre_pixel) continue;
      if (std::abs(map.range(q) - range) > max_jump) break;  // another surface
      offsets[found] = map.point(q) - centre;
      ring_position[found] = k;
      ++found;
      break;
    }
  }
  if (found < 2) return false;

  // Fan of triangles between consecutive neighbours that are less than 180 degrees apart.
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int triangles = 0;
  for (int i = 0; i < found; ++i) {
    const int j = i + 1 < found ? i + 1 : 0;  // wraps without a division, as above
    const int gap = (ring_position[j] - ring_position[i]) & 7;  // ring distance, 0 .. 7
    if (gap == 0 || gap > 3) continue;
    sum += offsets[i].cross(offsets[j]);
    ++triangles;
    if (found == 2) break;  // i = 1 -> j = 0 would add the same triangle reversed
  }
  const float norm = sum.norm();
  if (triangles < config_.min_triangles || !(norm > 1e-12F)) return false;
  Eigen::Vector3f n = sum / norm;

  const float off_plane = static_cast<float>(config_.max_off_plane_ratio);
  for (int i = 0; i < found; ++i) {
    if (std::abs(n.dot(offsets[i])) > off_plane * offsets[i].norm()) return false;
  }
  if (n.dot(centre) > 0.0F) n = -n;  // face the base origin
  *normal_B = n;
  return true;
}

}  // namespace uampc::mpc
