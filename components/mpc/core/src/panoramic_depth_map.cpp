#include "uampc/mpc/panoramic_depth_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "fast_atan2.hpp"

namespace uampc::mpc {

namespace {
constexpr double kPi = 3.14159265358979323846;
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
  winner_.assign(pixels, -1);
  points_B_.assign(pixels, Eigen::Vector3f::Zero());
  zbuffer_.assign(pixels, ~std::uint64_t{0});
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

void PanoramicDepthMap::render(const std::vector<Eigen::Vector3d>& points_W,
                               const Eigen::Isometry3d& T_WB) {
  if (points_W.size() >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument("PanoramicDepthMap: local map too large");
  }
  std::fill(zbuffer_.begin(), zbuffer_.end(), kEmpty);
  source_size_ = points_W.size();

  const Eigen::Matrix3d R_BW = T_WB.linear().transpose();
  const Eigen::Vector3d r_BW = -(R_BW * T_WB.translation());
  const double min2 = config_.min_range * config_.min_range;
  const double max2 = config_.max_range * config_.max_range;
  const double columns_per_rad = config_.width / (2.0 * kPi);
  const double rows_per_rad = config_.height / kPi;
  const int max_splat = std::max(std::min(config_.max_splat_radius_px, config_.width / 2 - 1), 0);
  const int width = config_.width;
  const int last_row = config_.height - 1;

  for (std::size_t i = 0; i < points_W.size(); ++i) {
    const Eigen::Vector3d p = R_BW * points_W[i] + r_BW;
    const double horizontal2 = p.x() * p.x() + p.y() * p.y();
    const double r2 = horizontal2 + p.z() * p.z();
    if (!(r2 >= min2 && r2 <= max2)) continue;  // also rejects NaN

    // Eq. 5; asin(z / r) is computed as atan2(z, sqrt(x^2 + y^2)), the same angle.
    const double horizontal = std::sqrt(horizontal2);
    const double azimuth = detail::fastAtan2(p.y(), p.x());
    const double elevation = detail::fastAtan2(p.z(), horizontal);
    int u = static_cast<int>((azimuth + kPi) * columns_per_rad);  // >= 0, so truncation = floor
    if (u >= width) u -= width;                                    // azimuth == +pi
    const int v = std::min(static_cast<int>((0.5 * kPi - elevation) * rows_per_rad), last_row);
    const double range = std::sqrt(r2);
    const std::uint64_t entry = pack(static_cast<float>(range), static_cast<std::uint32_t>(i));

    const double half_width = 0.5 * config_.point_spacing / range;  // rad
    const int splat_v = std::min(static_cast<int>(half_width * rows_per_rad), max_splat);
    const double cos_elevation = std::max(horizontal / range, 0.1);
    const int splat_u = std::min(
        static_cast<int>(half_width * columns_per_rad / cos_elevation), max_splat);
    if (splat_v == 0 && splat_u == 0) {  // the common case: far points
      std::uint64_t& z = zbuffer_[pixelIndex(u, v)];
      z = std::min(z, entry);
      continue;
    }
    for (int vv = std::max(v - splat_v, 0); vv <= std::min(v + splat_v, last_row); ++vv) {
      std::uint64_t* row_begin = &zbuffer_[pixelIndex(0, vv)];
      for (int du = -splat_u; du <= splat_u; ++du) {
        int uu = u + du;
        if (uu < 0) uu += width;
        if (uu >= width) uu -= width;
        row_begin[uu] = std::min(row_begin[uu], entry);
      }
    }
  }

  // Unpack into the depth image, the winners and their base-frame coordinates.
  occupied_count_ = 0;
  for (std::size_t pixel = 0; pixel < zbuffer_.size(); ++pixel) {
    const std::uint64_t z = zbuffer_[pixel];
    if (z == kEmpty) {
      depth_[pixel] = 0.0F;
      winner_[pixel] = -1;
      continue;
    }
    const auto index = static_cast<std::int32_t>(z & 0xffffffffU);
    const auto bits = static_cast<std::uint32_t>(z >> 32);
    std::memcpy(&depth_[pixel], &bits, sizeof bits);
    winner_[pixel] = index;
    points_B_[pixel] = (R_BW * points_W[index] + r_BW).cast<float>();
    ++occupied_count_;
  }
}

int PanoramicDepthMap::lookup(int u, int v, int search_radius) const {
  const int centre = pixelIndex(u, v);
  if (occupied(centre)) return centre;
  int best = -1;
  float best_range = 0.0F;
  for (int dv = -search_radius; dv <= search_radius; ++dv) {
    const int vv = v + dv;
    if (vv < 0 || vv >= config_.height) continue;
    for (int du = -search_radius; du <= search_radius; ++du) {
      int uu = (u + du) % config_.width;
      if (uu < 0) uu += config_.width;
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
