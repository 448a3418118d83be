#include "uampc/mpc/uncertainty_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "angles.hpp"

namespace uampc::mpc {

namespace {
using detail::kTwoPi;

// Grid values from lo to hi (inclusive within a small tolerance) every step; for a full circle
// the end point is the start point again and is left out.
std::vector<double> gridValues(double lo, double hi, double step, bool periodic) {
  std::vector<double> values;
  const double span = hi - lo;
  const bool full_circle = periodic && span >= kTwoPi - 1e-9;
  const int count =
      full_circle ? static_cast<int>(std::round(kTwoPi / step)) : static_cast<int>(std::floor(span / step + 1e-9)) + 1;
  for (int i = 0; i < count; ++i) values.push_back(lo + i * step);
  return values;
}
}  // namespace

UncertaintyModel::UncertaintyModel() : UncertaintyModel(Config{}) {}

UncertaintyModel::UncertaintyModel(const Config& config) : config_(config) {
  const LidarFieldOfView& fov = config_.field_of_view;
  if (!(config_.azimuth_step > 0.0) || !(config_.elevation_step > 0.0)) {
    throw std::invalid_argument("UncertaintyModel: azimuth_step and elevation_step must be > 0");
  }
  if (!(config_.eigenvalue_floor > 0.0)) {
    throw std::invalid_argument("UncertaintyModel: eigenvalue_floor must be > 0");
  }
  if (!(fov.azimuth_max >= fov.azimuth_min) || !(fov.elevation_max >= fov.elevation_min)) {
    throw std::invalid_argument("UncertaintyModel: field of view has max < min");
  }
  if (config_.lookup_radius_px < 0) {
    throw std::invalid_argument("UncertaintyModel: lookup_radius_px must be >= 0");
  }
  if (!(config_.range_weight_saturation >= 0.0) || !std::isfinite(config_.range_weight_saturation)) {
    throw std::invalid_argument("UncertaintyModel: range_weight_saturation must be finite and >= 0");
  }

  // Rays at theta = 0: the motor frame coincides with the base frame.
  const Eigen::Matrix3d R_BL0 = frames::lidarPoseInBase(0.0, config_.calibration).linear();
  for (double azimuth : gridValues(fov.azimuth_min, fov.azimuth_max, config_.azimuth_step, true)) {
    for (double elevation : gridValues(fov.elevation_min, fov.elevation_max, config_.elevation_step, false)) {
      const Eigen::Vector3d d_L(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
      const Eigen::Vector3d d_B = R_BL0 * d_L;
      rays_L_.push_back(d_L);
      ray_azimuth_at_zero_.push_back(std::atan2(d_B.y(), d_B.x()));
      ray_elevation_.push_back(std::atan2(d_B.z(), std::hypot(d_B.x(), d_B.y())));
    }
  }
}

Vector6d UncertaintyModel::pointToPlaneJacobian(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  Vector6d J;
  J << p.cross(n), n;
  return J;
}

// The ray lookup of one control step, prepared once for all candidate angles: each ray's row and
// its column offset at theta = 0 (in columns, within [0, W)).
struct UncertaintyModel::RayTable {
  std::vector<int> rows;
  std::vector<double> columns_at_zero;
  double columns_per_rad = 0.0;
};

UncertaintyModel::RayTable UncertaintyModel::rayTable(const PanoramicDepthMap& map) const {
  RayTable table;
  table.columns_per_rad = map.width() / kTwoPi;
  for (std::size_t k = 0; k < ray_elevation_.size(); ++k) {
    table.rows.push_back(map.row(ray_elevation_[k]));
    // Eq. 5 column, unfloored: (azimuth + pi) / (2 pi) * W, azimuth in [-pi, pi].
    const double column = (ray_azimuth_at_zero_[k] + 0.5 * kTwoPi) * table.columns_per_rad;
    table.columns_at_zero.push_back(std::min(column, std::nextafter(map.width(), 0.0)));
  }
  return table;
}

// What a ray through a pixel contributes, resolved on the first ray through it and reused by all
// later rays and candidate angles of the same call: the 72 x 864 rays of a control step pass
// through a few thousand distinct pixels, and resolving one (neighbourhood lookup, per-point normal
// cache, Jacobian) costs cache misses in arrays as large as the local map. A pixel's Jacobian
// depends on the pixel alone (its point's normal is estimated at the point's own pixel), so the
// memo changes no Lambda: each is the same sum, in the same ray order, as without it. (Measured and
// rejected earlier: resolving all those pixels up front, in raster order, cost more in extra passes
// over the panorama than it saved.)
struct UncertaintyModel::PixelJacobians {
  static constexpr std::int32_t kUnresolved = -2;
  static constexpr std::int32_t kNoHit = -1;  // no surface, or no reliable normal

  std::vector<std::int32_t> of_pixel;  // kUnresolved, kNoHit or an index into jacobians
  std::vector<Vector6d> jacobians;     // J = [ p x n ; n ] (base axes, see the header)
  std::vector<std::int32_t> ray_hits;  // scratch: per angle and ray, the ray's entry of of_pixel

  // Kept per thread: the buffers are reused, so a control step allocates nothing once they grew.
  static PixelJacobians& forMap(const PanoramicDepthMap& map) {
    thread_local PixelJacobians pixels;
    pixels.of_pixel.assign(static_cast<std::size_t>(map.width()) * map.height(), kUnresolved);
    pixels.jacobians.clear();
    return pixels;
  }
};

double UncertaintyModel::rangeWeightSaturation(double voxel_size, double points_per_frame,
                                               const LidarFieldOfView& fov) {
  const double solid_angle =
      (fov.azimuth_max - fov.azimuth_min) * (std::sin(fov.elevation_max) - std::sin(fov.elevation_min));
  return voxel_size * std::sqrt(points_per_frame / solid_angle);
}

double UncertaintyModel::rayWeight(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  const double range_squared = double(p.squaredNorm());
  const double cos_incidence = std::max(std::abs(double(p.dot(n))) / std::sqrt(range_squared), 0.05);
  const double r_sat = config_.range_weight_saturation;
  return std::min(1.0, range_squared / (r_sat * r_sat * cos_incidence));
}

std::int32_t UncertaintyModel::resolve(const PanoramicDepthMap& map, DepthMapNormals& normals, int u, int v,
                                       PixelJacobians& pixels) const {
  const int pixel = map.lookup(u, v, config_.lookup_radius_px);
  if (pixel < 0) return PixelJacobians::kNoHit;
  const Eigen::Vector3f* n = normals.normal(pixel);
  if (n == nullptr) return PixelJacobians::kNoHit;
  const Eigen::Vector3f& p = map.point(pixel);
  Vector6d J;
  J << double(p.y()) * n->z() - double(p.z()) * n->y(), double(p.z()) * n->x() - double(p.x()) * n->z(),
      double(p.x()) * n->y() - double(p.y()) * n->x(), n->x(), n->y(), n->z();
  if (config_.range_weight_saturation > 0.0) J *= std::sqrt(rayWeight(p, *n));
  pixels.jacobians.push_back(J);
  return static_cast<std::int32_t>(pixels.jacobians.size() - 1);
}

std::vector<Matrix6d> UncertaintyModel::informationSamples(const PanoramicDepthMap& map, DepthMapNormals& normals,
                                                         double theta_start, double step, int count) const {
  const RayTable table = rayTable(map);
  PixelJacobians& pixels = PixelJacobians::forMap(map);
  const int width = map.width();
  const std::size_t rays = table.rows.size();
  const std::size_t samples = static_cast<std::size_t>(std::max(count, 0));
  // Each candidate angle in columns, reduced to [0, W): the same column arithmetic for any number
  // of turns.
  std::vector<double> shifts(samples);
  for (std::size_t s = 0; s < samples; ++s) {
    double shift = (theta_start + static_cast<double>(s) * step) * table.columns_per_rad;
    shifts[s] = shift - width * std::floor(shift / width);
  }
  // Pass 1, ray by ray: the Jacobian of each ray at each angle. A ray keeps its row at every
  // angle (R_BM(theta) turns about the base z axis), so its angles walk along one row of the
  // panorama, the memo and the normals' cache: nearby memory, where angle by angle the 864 rays
  // jumped across the whole panorama and most look-ups missed the cache. The order does not
  // change a result: a pixel's Jacobian depends only on the pixel (its point's normal is
  // estimated at the point's own pixel, DepthMapNormals).
  pixels.ray_hits.resize(rays * samples);
  for (std::size_t k = 0; k < rays; ++k) {
    const int row = table.rows[k];
    const double column_at_zero = table.columns_at_zero[k];
    std::int32_t* of_row = &pixels.of_pixel[map.pixelIndex(0, row)];
    for (std::size_t s = 0; s < samples; ++s) {
      int u = static_cast<int>(column_at_zero + shifts[s]);  // in [0, 2W)
      if (u >= width) u -= width;
      std::int32_t& hit = of_row[u];
      if (hit == PixelJacobians::kUnresolved) hit = resolve(map, normals, u, row, pixels);
      pixels.ray_hits[s * rays + k] = hit;
    }
  }
  // Pass 2, angle by angle: the upper triangle of Lambda = sum_k J_k J_k^T, 21 products per ray
  // instead of 36, summed in ray order.
  std::vector<Matrix6d> lambdas(samples);
  for (std::size_t s = 0; s < samples; ++s) {
    const std::int32_t* hits = &pixels.ray_hits[s * rays];
    double upper[21] = {};
    for (std::size_t k = 0; k < rays; ++k) {
      if (hits[k] == PixelJacobians::kNoHit) continue;
      const double* J = pixels.jacobians[hits[k]].data();
      int e = 0;
      for (int r = 0; r < 6; ++r) {
        for (int c = r; c < 6; ++c) upper[e++] += J[r] * J[c];
      }
    }
    int e = 0;
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) {
        lambdas[s](r, c) = upper[e];
        lambdas[s](c, r) = upper[e];
        ++e;
      }
    }
  }
  return lambdas;
}

Matrix6d UncertaintyModel::information(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta) const {
  return informationSamples(map, normals, theta, 0.0, 1).front();
}

double UncertaintyModel::aOptimality(const Matrix6d& information) const {
  if (!information.allFinite()) return maxUncertainty();
  // Usual case first, with two Cholesky factorisations instead of an eigen-decomposition: if
  // Lambda - floor I is positive definite, every eigenvalue is above the floor, the clamp changes
  // nothing, and trace(Lambda^-1) = ||L^-1||_F^2 for Lambda = L L^T. (The min only guards the
  // documented bound against rounding when all eigenvalues sit at the floor.)
  const Matrix6d above_floor = information - config_.eigenvalue_floor * Matrix6d::Identity();
  if (Eigen::LLT<Matrix6d>(above_floor).info() == Eigen::Success) {
    const Eigen::LLT<Matrix6d> cholesky(information);
    const double trace = cholesky.matrixL().solve(Matrix6d::Identity()).squaredNorm();
    return std::min(trace, maxUncertainty());
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(information, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) return maxUncertainty();
  double trace = 0.0;
  for (int i = 0; i < 6; ++i) {
    trace += 1.0 / std::max(solver.eigenvalues()[i], config_.eigenvalue_floor);
  }
  return trace;
}

double UncertaintyModel::uncertainty(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta) const {
  return aOptimality(information(map, normals, theta));
}

std::vector<double> UncertaintyModel::sample(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta_start,
                                             double step, int count) const {
  const std::vector<Matrix6d> lambdas = informationSamples(map, normals, theta_start, step, count);
  std::vector<double> samples(lambdas.size());
  for (std::size_t s = 0; s < lambdas.size(); ++s) samples[s] = aOptimality(lambdas[s]);
  return samples;
}

}  // namespace uampc::mpc
