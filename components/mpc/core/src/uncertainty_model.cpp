#include "uampc/mpc/uncertainty_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <stdexcept>

namespace uampc::mpc {

namespace {
constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
constexpr std::int32_t kUnresolved = -2;  // pixel slots of the ray table, see RayTable
constexpr std::int32_t kNoJacobian = -1;

// Grid values from lo to hi (inclusive within a small tolerance) every step; for a full circle
// the end point is the start point again and is left out.
std::vector<double> gridValues(double lo, double hi, double step, bool periodic) {
  std::vector<double> values;
  const double span = hi - lo;
  const bool full_circle = periodic && span >= kTwoPi - 1e-9;
  const int count = full_circle ? static_cast<int>(std::round(kTwoPi / step))
                                : static_cast<int>(std::floor(span / step + 1e-9)) + 1;
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

  // Rays at theta = 0: the motor frame coincides with the base frame.
  const Eigen::Matrix3d R_BL0 = frames::lidarPoseInBase(0.0, config_.calibration).linear();
  for (double azimuth : gridValues(fov.azimuth_min, fov.azimuth_max, config_.azimuth_step, true)) {
    for (double elevation :
         gridValues(fov.elevation_min, fov.elevation_max, config_.elevation_step, false)) {
      const Eigen::Vector3d d_L(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const Eigen::Vector3d d_B = R_BL0 * d_L;
      rays_L_.push_back(d_L);
      ray_azimuth_at_zero_.push_back(std::atan2(d_B.y(), d_B.x()));
      ray_elevation_.push_back(std::atan2(d_B.z(), std::hypot(d_B.x(), d_B.y())));
    }
  }
}

Vector6d UncertaintyModel::pointToPlaneJacobian(const Eigen::Vector3d& p,
                                                const Eigen::Vector3d& n) {
  Vector6d J;
  J << p.cross(n), n;
  return J;
}

// The ray lookups of one control step, prepared once for all candidate angles.
//
// The 72 samples of a step cast about 60k rays into a 65k-pixel panorama. Resolving what a ray
// through a pixel contributes (hole filling by lookup(), the normal, the Jacobian) touches the
// map's arrays and its neighbourhood at random when done ray by ray, and cache misses then cost
// more than the arithmetic. So a step first marks every pixel some ray of some sample goes
// through, resolves the marked pixels in raster order (the neighbourhoods of consecutive pixels
// overlap), and only then sums J J^T per sample, reading one slot per ray. Jacobians are stored
// once per local-map point (a splatted point covers many pixels), in double, as computed before.
// A point's normal is therefore estimated at the first of its pixels in raster order that a ray
// asks for (DepthMapNormals caches it per point).
struct UncertaintyModel::RayTable {
  double columns_per_rad = 0.0;
  std::vector<int> rows;
  std::vector<int> row_offsets;          // row * W
  std::vector<double> columns_at_zero;   // column offset at theta = 0, in [0, W)
  std::vector<std::int32_t> pixel_slot;  // per pixel: kUnresolved, kNoJacobian or a slot
  std::vector<std::array<double, 6>> jacobians;  // per slot: J = [ p x n ; n ] in base axes
};

UncertaintyModel::RayTable UncertaintyModel::rayTable(const PanoramicDepthMap& map) const {
  RayTable table;
  table.columns_per_rad = map.width() / kTwoPi;
  for (std::size_t k = 0; k < ray_elevation_.size(); ++k) {
    table.rows.push_back(map.row(ray_elevation_[k]));
    table.row_offsets.push_back(map.pixelIndex(0, table.rows.back()));
    // Eq. 5 column, unfloored: (azimuth + pi) / (2 pi) * W, azimuth in [-pi, pi].
    const double column = (ray_azimuth_at_zero_[k] + 0.5 * kTwoPi) * table.columns_per_rad;
    table.columns_at_zero.push_back(std::min(column, std::nextafter(map.width(), 0.0)));
  }
  table.pixel_slot.assign(static_cast<std::size_t>(map.width()) * map.height(), kNoJacobian);
  return table;
}

namespace {

// theta in columns, reduced to [0, W): the same column arithmetic for any number of turns.
double columnShift(double theta, double columns_per_rad, int width) {
  const double shift = theta * columns_per_rad;
  return shift - width * std::floor(shift / width);
}

// Column of ray k at a column shift: R_BM(theta) adds theta to the azimuth.
int rayColumn(double column_at_zero, double shift, int width) {
  const int u = static_cast<int>(column_at_zero + shift);  // in [0, 2W)
  return u >= width ? u - width : u;
}

}  // namespace

void UncertaintyModel::resolve(const PanoramicDepthMap& map, DepthMapNormals& normals,
                               const std::vector<double>& shifts, RayTable& table) const {
  const int width = map.width();
  for (double shift : shifts) {
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
      const int u = rayColumn(table.columns_at_zero[k], shift, width);
      table.pixel_slot[table.row_offsets[k] + u] = kUnresolved;
    }
  }
  std::vector<std::int32_t> point_slot(map.sourceSize(), kUnresolved);
  for (std::size_t centre = 0; centre < table.pixel_slot.size(); ++centre) {
    if (table.pixel_slot[centre] != kUnresolved) continue;
    std::int32_t& result = table.pixel_slot[centre];
    result = kNoJacobian;
    const int pixel = map.lookup(static_cast<int>(centre) % width,
                                 static_cast<int>(centre) / width, config_.lookup_radius_px);
    if (pixel < 0) continue;
    std::int32_t& slot = point_slot[map.pointIndex(pixel)];
    if (slot == kUnresolved) {
      const Eigen::Vector3f* n = normals.normal(pixel);
      slot = kNoJacobian;
      if (n != nullptr) {
        // J = [ p x n ; n ] in base axes (see the header), from the float map in double.
        const Eigen::Vector3f& p = map.point(pixel);
        table.jacobians.push_back({double(p.y()) * n->z() - double(p.z()) * n->y(),
                                   double(p.z()) * n->x() - double(p.x()) * n->z(),
                                   double(p.x()) * n->y() - double(p.y()) * n->x(),
                                   n->x(), n->y(), n->z()});
        slot = static_cast<std::int32_t>(table.jacobians.size() - 1);
      }
    }
    result = slot;
  }
}

Matrix6d UncertaintyModel::accumulate(const RayTable& table, int width, double shift) const {
  // Upper triangle of sum_k J_k J_k^T, accumulated by hand: 21 products per ray instead of 36.
  double upper[21] = {};
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const int u = rayColumn(table.columns_at_zero[k], shift, width);
    const std::int32_t slot = table.pixel_slot[table.row_offsets[k] + u];
    if (slot < 0) continue;
    const std::array<double, 6>& J = table.jacobians[slot];
    int e = 0;
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) upper[e++] += J[r] * J[c];
    }
  }
  Matrix6d lambda;
  int e = 0;
  for (int r = 0; r < 6; ++r) {
    for (int c = r; c < 6; ++c) {
      lambda(r, c) = upper[e];
      lambda(c, r) = upper[e];
      ++e;
    }
  }
  return lambda;
}

Matrix6d UncertaintyModel::information(const PanoramicDepthMap& map, DepthMapNormals& normals,
                                       double theta) const {
  RayTable table = rayTable(map);
  const double shift = columnShift(theta, table.columns_per_rad, map.width());
  resolve(map, normals, {shift}, table);
  return accumulate(table, map.width(), shift);
}

double UncertaintyModel::aOptimality(const Matrix6d& information) const {
  if (!information.allFinite()) return maxUncertainty();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(information, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) return maxUncertainty();
  double trace = 0.0;
  for (int i = 0; i < 6; ++i) {
    trace += 1.0 / std::max(solver.eigenvalues()[i], config_.eigenvalue_floor);
  }
  return trace;
}

double UncertaintyModel::uncertainty(const PanoramicDepthMap& map, DepthMapNormals& normals,
                                     double theta) const {
  return aOptimality(information(map, normals, theta));
}

std::vector<double> UncertaintyModel::sample(const PanoramicDepthMap& map,
                                             DepthMapNormals& normals, double theta_start,
                                             double step, int count) const {
  RayTable table = rayTable(map);
  std::vector<double> shifts;
  for (int s = 0; s < count; ++s) {
    shifts.push_back(columnShift(theta_start + s * step, table.columns_per_rad, map.width()));
  }
  resolve(map, normals, shifts, table);
  std::vector<double> samples;
  for (double shift : shifts) samples.push_back(aOptimality(accumulate(table, map.width(), shift)));
  return samples;
}

}  // namespace uampc::mpc
