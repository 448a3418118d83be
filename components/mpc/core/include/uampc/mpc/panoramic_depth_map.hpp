// Panoramic depth map of the local map around the base origin (paper, Eq. 5).
//
// The local map (world frame) is moved into the base frame, p_B = R_WB^T (p_W - r_WB), and every
// point is binned by its direction:
//
//   u = atan2(y, x) / (2 pi) * W,   v = asin(z / r) / pi * H                            (Eq. 5)
//
// with the offsets that make indices non-negative and the image upright:
//   column u = floor((atan2(y, x) + pi) / (2 pi) * W)   column 0 looks along azimuth -pi,
//   row    v = floor((pi/2 - asin(z / r)) / pi * H)      row 0 looks straight up (zenith).
// Each pixel keeps the nearest point (smallest range) that falls in it, with that point's index in
// the input cloud and its base-frame coordinates.
//
// Splatting: an LO local map is voxel-downsampled (0.3 m), so near surfaces are sparse in a
// 1-degree panorama (at 2 m, 0.3 m is 8.6 degrees) and rays would slip through the gaps. Each
// point therefore covers the pixels of its footprint, half-width 0.5 * point_spacing / range
// (radians, widened in azimuth by 1 / cos(elevation of its pixel row's centre), rounded down to
// whole pixels: one-pixel gaps are bridged by lookup()), capped at max_splat_radius_px; nearest
// still wins in every pixel. A splatted pixel stores the point itself (not a ray-surface
// intersection). point_spacing = 0 renders every point into exactly one pixel. The axes are the
// base axes, so a LiDAR ray R_BM(theta) R_ML d_L can be looked up directly; ray origins are taken
// at the base origin (the LiDAR offset r_ML is centimetres against ranges of metres).
//
// Rendering cost (a 100k-point local map within a few milliseconds, see bench/mpc_bench.cpp):
// points are projected in blocks by a branch-free float loop that the compiler vectorises, and
// only the nearest point of each pixel is splatted. That thinning is exact, not an approximation:
// the footprint is centred on the point's pixel and its size depends only on the range and the
// row, never growing with the range, so the nearest point of a pixel covers the footprint of every
// farther point of the same pixel and beats it in each of those pixels.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uampc::mpc {

class PanoramicDepthMap {
 public:
  struct Config {
    // 1 degree per pixel. tools/u_check ranks the motor angles by U closer to what the LO
    // achieves with it than with 2-degree pixels (Spearman with the posterior covariance, campus
    // poor row 0.74 against 0.67, corridor with doors 0.35 against 0.23; docs/results/u-check.md),
    // for about 4.6 instead of 2.5 ms per control step (mpc_bench).
    int width = 360;              // columns over 2 pi of azimuth
    int height = 180;             // rows over pi of elevation
    double min_range = 0.5;       // m, closer points are ignored (robot body, degenerate directions)
    double max_range = 40.0;      // m, farther points are ignored (the LiDAR would not see them)
    double point_spacing = 0.3;   // m, typical distance between local-map points (splat size)
    int max_splat_radius_px = 2;  // cap of the splat half-width, pixels
  };

  PanoramicDepthMap();  // default Config
  // Throws std::invalid_argument on a non-positive size or an empty range window.
  explicit PanoramicDepthMap(const Config& config);

  // Renders the panorama around the base origin; replaces the previous content.
  // Points that are not finite or lie outside [min_range, max_range] are skipped.
  void render(const std::vector<Eigen::Vector3d>& points_W, const Eigen::Isometry3d& T_WB);
  // render() for float points (the LO's local map arrives as float32): the same pixels and ranges
  // as rendering the points widened to double, without building that double copy.
  void renderFloat(const std::vector<Eigen::Vector3f>& points_W, const Eigen::Isometry3d& T_WB);

  int width() const { return config_.width; }
  int height() const { return config_.height; }
  const Config& config() const { return config_; }

  // Pixel geometry (Eq. 5). column() accepts any azimuth (multi-turn) and wraps it.
  int column(double azimuth) const;
  int row(double elevation) const;
  int pixelIndex(int u, int v) const { return v * config_.width + u; }
  // Pixel that a base-frame direction falls in (the direction need not be unit length).
  int pixelOf(const Eigen::Vector3d& direction_B) const;

  bool occupied(int pixel) const { return pixels_[pixel].centre >= 0; }
  float range(int pixel) const { return depth_[pixel]; }  // m, 0 when empty
  std::int32_t pointIndex(int pixel) const {              // -1 when empty
    const std::int32_t centre = pixels_[pixel].centre;
    return centre < 0 ? -1 : static_cast<std::int32_t>(centre_[centre] & 0xffffffffU);
  }
  // The winning point's own pixel (where Eq. 5 puts it, and where it is the nearest point): one
  // per winning point, so it names the point within the panorama. -1 when empty.
  std::int32_t centrePixel(int pixel) const { return pixels_[pixel].centre; }
  // Winning point in the base frame (base axes, relative to the base origin); valid if occupied.
  const Eigen::Vector3f& point(int pixel) const { return pixels_[pixel].point_B; }
  // A winning point named by its own pixel (a centrePixel() >= 0), also where a nearer point's
  // splat covers that pixel and point() there is the other point.
  const Eigen::Vector3f& centrePoint(std::int32_t centre_pixel) const { return centre_points_[centre_pixel]; }
  std::size_t occupiedCount() const { return occupied_count_; }

  // The occupied pixel a ray through (u, v) hits: (u, v) itself if occupied, otherwise the nearest
  // (smallest range) occupied pixel within search_radius pixels (columns wrap, rows clamp), so a
  // ray through a small hole of a sparse map still finds its surface. -1 when there is none.
  int lookup(int u, int v, int search_radius) const;

  // The depth image: height() rows of width() floats, row-major, range in metres, 0 for an empty
  // pixel (the usual "no return" value of 32FC1 depth images). Row 0 is the zenith.
  const std::vector<float>& depthImage() const { return depth_; }

 private:
  template <class Point>
  void renderPoints(const std::vector<Point>& points_W, const Eigen::Isometry3d& T_WB);

  Config config_;
  // Packed (range, index) z-buffers while rendering: the nearest point whose own pixel this is,
  // and the splatted result, with splat_pad_ extra columns on each side so that a footprint never
  // wraps inside the inner loop (the pads are folded back onto the other edge afterwards).
  std::vector<std::uint64_t> centre_;
  std::vector<Eigen::Vector3f> centre_points_;  // base-frame coordinates of centre_'s points
  std::vector<std::uint64_t> zbuffer_;
  int splat_pad_ = 0;
  std::vector<float> splat_columns_per_range_;  // per row: azimuth half-width (px) * range
  std::vector<float> depth_;
  // Winner and its coordinates side by side (16 bytes): normal estimation walks the panorama
  // reading both, and one cache line per visited pixel instead of two halves its misses.
  struct PixelPoint {
    Eigen::Vector3f point_B;
    std::int32_t centre;  // centrePixel(), -1 when empty
  };
  std::vector<PixelPoint> pixels_;
  std::size_t occupied_count_ = 0;
};

}  // namespace uampc::mpc
