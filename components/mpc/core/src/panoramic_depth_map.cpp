#include "uampc/mpc/panoramic_depth_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "angles.hpp"
#include "panorama_kernels.hpp"

namespace uampc::mpc {

namespace {
using detail::kPi;
}  // namespace

PanoramicDepthMap::PanoramicDepthMap() : PanoramicDepthMap(Config{}) {}

PanoramicDepthMap::PanoramicDepthMap(const Config& config) : config_(config) {
  if (config_.width <= 0 || config_.height <= 0) {
    throw std::invalid_argument("PanoramicDepthMap: width and height must be positive");
  }
  if (!(config_.min_range >= 0.0) || !(config_.max_range > config_.min_range)) {
    throw std::invalid_argument("PanoramicDepthMap: need 0 <= min_range < max_range");
  }
  if (!(config_.point_spacing >= 0.0) || config_.max_splat_radius_px < 0) {
    throw std::invalid_argument(
        "PanoramicDepthMap: point_spacing and max_splat_radius_px must be >= 0");
  }
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  depth_.assign(pixels, 0.0F);
  pixels_.assign(pixels, PixelPoint{Eigen::Vector3f::Zero(), -1});
  centre_.assign(pixels, ~std::uint64_t{0});
  centre_points_.assign(pixels, Eigen::Vector3f::Zero());
  splat_pad_ = std::max(std::min(config_.max_splat_radius_px, config_.width / 2 - 1), 0);
  zbuffer_.assign(static_cast<std::size_t>(config_.width + 2 * splat_pad_) * config_.height,
                  ~std::uint64_t{0});
  // Azimuth half-width of a footprint in pixels, times the range: 0.5 * spacing / cos(elevation)
  // in radians, at the elevation of the row's centre (floored at cos = 0.1 near the poles).
  const double columns_per_rad = config_.width / (2.0 * kPi);
  for (int v = 0; v < config_.height; ++v) {
    const double elevation = 0.5 * kPi - (v + 0.5) * kPi / config_.height;
    splat_columns_per_range_.push_back(static_cast<float>(
        0.5 * config_.point_spacing * columns_per_rad / std::max(std::cos(elevation), 0.1)));
  }
}

int PanoramicDepthMap::column(double azimuth) const {
  const double x = (azimuth + kPi) * (config_.width / (2.0 * kPi));
  long long u = static_cast<long long>(std::floor(x)) % config_.width;
  if (u < 0) u += config_.width;
  return static_cast<int>(u);
}

int PanoramicDepthMap::row(double elevation) const {
  const int v = static_cast<int>(std::floor((0.5 * kPi - elevation) * (config_.height / kPi)));
  return std::clamp(v, 0, config_.height - 1);
}

int PanoramicDepthMap::pixelOf(const Eigen::Vector3d& d) const {
  const double azimuth = std::atan2(d.y(), d.x());
  const double elevation = std::atan2(d.z(), std::hypot(d.x(), d.y()));
  return pixelIndex(column(azimuth), row(elevation));
}

// Z-buffer entry: the range's float bits in the high word, the point index in the low word. Ranges
// are positive, and positive IEEE floats order like their bit patterns, so "nearest wins" is an
// unsigned min of the packed words: one compare per splatted pixel, no branch on three arrays.
namespace {
constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

std::uint64_t pack(float range, std::uint32_t index) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &range, sizeof bits);
  return (static_cast<std::uint64_t>(bits) << 32) | index;
}
}  // namespace

void PanoramicDepthMap::render(const std::vector<Eigen::Vector3d>& points_W, const Eigen::Isometry3d& T_WB) {
  renderPoints(points_W, T_WB);
}

void PanoramicDepthMap::renderFloat(const std::vector<Eigen::Vector3f>& points_W, const Eigen::Isometry3d& T_WB) {
  renderPoints(points_W, T_WB);
}

template <class Point>
void PanoramicDepthMap::renderPoints(const std::vector<Point>& points_W, const Eigen::Isometry3d& T_WB) {
  if (points_W.size() >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument("PanoramicDepthMap: local map too large");
  }
  std::fill(centre_.begin(), centre_.end(), kEmpty);
  std::fill(zbuffer_.begin(), zbuffer_.end(), kEmpty);

  const int width = config_.width;
  const int height = config_.height;

  // Pass 1: every point into its own pixel (Eq. 5), nearest wins. Float is ample for binning
  // (1e-7 relative against a 1-degree pixel); the translation is removed in double first. Per
  // block: binned without branches (vectorised, panorama_kernels.hpp), then scattered into the
  // z-buffer (scalar).
  {
    const detail::BaseFrameTransform T{T_WB.translation(), T_WB.linear().transpose().cast<float>()};
    detail::PanoramaProjection projection;
    projection.min_range2 = static_cast<float>(config_.min_range * config_.min_range);
    projection.max_range2 = static_cast<float>(config_.max_range * config_.max_range);
    projection.columns_per_rad = static_cast<float>(width / (2.0 * kPi));
    projection.rows_per_rad = static_cast<float>(height / kPi);
    projection.width = width;
    projection.height = height;
    constexpr int kBlock = detail::kBinBlock;
    float range[kBlock];
    std::int32_t column[kBlock], row[kBlock];
    for (std::size_t begin = 0; begin < points_W.size(); begin += kBlock) {
      const int n = static_cast<int>(std::min<std::size_t>(kBlock, points_W.size() - begin));
      detail::binPoints(&points_W[begin], n, T, projection, range, column, row);
      for (int j = 0; j < n; ++j) {
        if (row[j] < 0) continue;
        const int pixel = pixelIndex(column[j], row[j]);
        const std::uint64_t candidate = pack(range[j], static_cast<std::uint32_t>(begin + j));
        // A select, not a branch: whether a point is the nearest so far is unpredictable.
        centre_[pixel] = std::min(centre_[pixel], candidate);
      }
    }
    // The base-frame coordinates of each pixel's nearest point, recomputed from its index (the
    // same operations, the same bits as the block above). Storing them in the scatter loop cost a
    // 12-byte random write per point; here it is one gather per occupied pixel, in raster order.
    for (std::size_t pixel = 0; pixel < centre_.size(); ++pixel) {
      if (centre_[pixel] == kEmpty) continue;
      centre_points_[pixel] = detail::baseFramePoint(points_W[centre_[pixel] & 0xffffffffU], T);
    }
  }

  // Pass 2: splat each pixel's nearest point over its footprint (exact thinning, see the header).
  // The footprint sizes are floor(c / range), monotone in the range as the thinning requires.
  // The splatted entry names the point by its own pixel (range bits, centre pixel): unpacking then
  // reads the point from a neighbouring pixel instead of gathering it from the whole local map.
  // (Equal float ranges are thus broken by centre pixel, not by point index.)
  const int pad = splat_pad_;
  const int padded_width = width + 2 * pad;
  const float rows_per_range =
      static_cast<float>(0.5 * config_.point_spacing * (height / kPi));
  for (int v = 0; v < height; ++v) {
    const std::uint64_t* centre_row = &centre_[pixelIndex(0, v)];
    const float columns_per_range = splat_columns_per_range_[v];
    for (int u = 0; u < width; ++u) {
      if (centre_row[u] == kEmpty) continue;
      const std::uint64_t entry =
          (centre_row[u] & ~std::uint64_t{0xffffffffU}) | static_cast<std::uint32_t>(pixelIndex(u, v));
      float range = 0.0F;
      const auto bits = static_cast<std::uint32_t>(entry >> 32);
      std::memcpy(&range, &bits, sizeof range);
      const float inverse_range = 1.0F / range;
      const int splat_v = std::min(static_cast<int>(rows_per_range * inverse_range), pad);
      const int splat_u = std::min(static_cast<int>(columns_per_range * inverse_range), pad);
      const int first_row = std::max(v - splat_v, 0);
      const int last_row = std::min(v + splat_v, height - 1);
      for (int vv = first_row; vv <= last_row; ++vv) {
        std::uint64_t* cell = &zbuffer_[static_cast<std::size_t>(vv) * padded_width + pad + u];
        for (int du = -splat_u; du <= splat_u; ++du) cell[du] = std::min(cell[du], entry);
      }
    }
  }

  // Fold the pads onto the columns they stand for, and unpack into the depth image, the winners
  // and their base-frame coordinates.
  occupied_count_ = 0;
  for (int v = 0; v < height; ++v) {
    std::uint64_t* row = &zbuffer_[static_cast<std::size_t>(v) * padded_width];
    for (int k = 0; k < pad; ++k) {
      row[pad + width - pad + k] = std::min(row[pad + width - pad + k], row[k]);  // left pad
      row[pad + k] = std::min(row[pad + k], row[pad + width + k]);               // right pad
    }
    for (int u = 0; u < width; ++u) {
      const int pixel = pixelIndex(u, v);
      const std::uint64_t entry = row[pad + u];
      if (entry == kEmpty) {
        depth_[pixel] = 0.0F;
        pixels_[pixel].centre = -1;
        continue;
      }
      const auto centre = static_cast<std::int32_t>(entry & 0xffffffffU);
      const auto bits = static_cast<std::uint32_t>(entry >> 32);
      std::memcpy(&depth_[pixel], &bits, sizeof bits);
      pixels_[pixel].centre = centre;
      pixels_[pixel].point_B = centre_points_[centre];
      ++occupied_count_;
    }
  }
}

int PanoramicDepthMap::lookup(int u, int v, int search_radius) const {
  const int centre = pixelIndex(u, v);
  if (occupied(centre)) return centre;
  int best = -1;
  float best_range = 0.0F;
  // The neighbourhood's columns, wrapped once (u - r .. u + r, within one turn for r < W): an
  // integer division per visited pixel cost most of a miss's look-up (outdoors, every ray into
  // the sky is one).
  const int width = config_.width;
  const int first_column = u - search_radius;
  const int columns = std::min(2 * search_radius + 1, width);
  for (int dv = -search_radius; dv <= search_radius; ++dv) {
    const int vv = v + dv;
    if (vv < 0 || vv >= config_.height) continue;
    int uu = first_column % width;
    if (uu < 0) uu += width;
    for (int i = 0; i < columns; ++i, uu = uu + 1 == width ? 0 : uu + 1) {
      const int pixel = pixelIndex(uu, vv);
      if (occupied(pixel) && (best < 0 || depth_[pixel] < best_range)) {
        best = pixel;
        best_range = depth_[pixel];
      }
    }
  }
  return best;
}

}  // namespace uampc::mpc
