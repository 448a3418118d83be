// U(theta): the predicted uncertainty of the LO if the LiDAR looks with motor angle theta
// (docs/dev/architecture.md section 1, UA-MPC steps 2-3).
//
// 1. The LiDAR field of view is sampled on a uniform grid of directions d_L (LiDAR frame).
// 2. Each ray is rotated into the base frame, d_B = R_BM(theta) R_ML d_L (uampc_frames), and looked
//    up in the panoramic depth map: the hit point p_k and its surface normal n_k.
// 3. Point-to-plane Jacobian of the residual n_k^T (R_WB p_k + r_WB - q_k) with respect to a
//    perturbation [dphi; dr] of the base pose (rotation applied on the world side about the base
//    origin, R_WB <- Exp(dphi) R_WB, r_WB <- r_WB + dr):
//        J_k = [ (R_WB p_k) x n_k ; n_k ]          (6x1)
//    with p_k in the BASE frame (relative to the base origin) and n_k in the WORLD frame.
// 4. Lambda = sum_k J_k J_k^T and U = trace(Lambda^-1) (A-optimality).
//
// Frames in the implementation: the depth map and its normals are in base axes, so we evaluate
// J_k^B = [ p_k x n_k^B ; n_k^B ] with n_k^B = R_WB^T n_k. Because (R a) x (R b) = R (a x b),
// J_k = diag(R_WB, R_WB) J_k^B, hence Lambda = D Lambda^B D^T with D orthogonal and
// trace(Lambda^-1) = trace((Lambda^B)^-1): U does not depend on which of the two axes is used,
// and R_WB is not needed. pointToPlaneJacobian() is the world-axes formula for reference and tests.
//
// Singular information: Lambda is positive semi-definite; along a direction no ray constrains
// (a corridor's axis, a plane's in-plane motion) an eigenvalue is zero. Each eigenvalue is clamped
// to eigenvalue_floor before inversion, so U <= 6 / eigenvalue_floor =: maxUncertainty(), finite
// and never NaN; an empty view gives exactly maxUncertainty(). An absolute (not relative) floor
// keeps U monotone: adding rays can only raise every eigenvalue of Lambda (Weyl), so U never grows.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/mpc/depth_map_normals.hpp"
#include "uampc/mpc/panoramic_depth_map.hpp"

namespace uampc::mpc {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// Field of view of the LiDAR in its own frame (rad), from the rig's LiDAR model.
using LidarFieldOfView = lidar::FieldOfView;

class UncertaintyModel {
 public:
  struct Config {
    LidarFieldOfView field_of_view = lidar::fieldOfView(lidar::livoxMid360());
    double azimuth_step = 5.0 * 3.14159265358979323846 / 180.0;    // rad, ray grid
    double elevation_step = 5.0 * 3.14159265358979323846 / 180.0;  // rad, ray grid
    frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
    double eigenvalue_floor = 1e-3;  // information floor; U <= 6 / eigenvalue_floor
    int lookup_radius_px = 1;        // a ray through an empty pixel takes the nearest neighbour
    // Weight of a ray by what the LO keeps of it (0: every ray weighs 1, Eq. 6 as written). The
    // LO downsamples each scan to one point per voxel, so a surface contributes in proportion
    // to its area (r^2 / cos(incidence) per unit solid angle) until the LiDAR's own point density
    // runs out, at the range r_sat where one voxel holds one raw point. With r_sat > 0 a ray
    // weighs min(1, (r / r_sat)^2 / |cos incidence|): near walls, which fill many rays but few
    // voxels, no longer dominate U. rangeWeightSaturation() computes r_sat for a LiDAR.
    double range_weight_saturation = 0.0;  // m
  };

  // r_sat = voxel * sqrt(points per frame / field-of-view solid angle): beyond it a 0.3 m voxel
  // holds less than one of the LiDAR's points (Mid-360, 20 000 points per 0.1 s frame over
  // 5.72 sr: 17.7 m).
  static double rangeWeightSaturation(double voxel_size, double points_per_frame, const LidarFieldOfView& fov);

  // Throws std::invalid_argument on non-positive steps or floor, or an empty field of view.
  UncertaintyModel();  // default Config
  explicit UncertaintyModel(const Config& config);

  // Lambda(theta) in base axes (see the header comment), from the rays that hit a surface with a
  // reliable normal. `normals` must have been reset() on `map`.
  Matrix6d information(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta) const;

  // U(theta) = trace(Lambda(theta)^-1) with the eigenvalue floor.
  double uncertainty(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta) const;

  // U at theta_start + s * step, s = 0 .. count - 1 (the samples U_s of the surrogate, Eq. 9).
  std::vector<double> sample(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta_start, double step,
                             int count) const;

  // trace(Lambda^-1) with every eigenvalue clamped to eigenvalue_floor; maxUncertainty() when
  // Lambda is not finite.
  double aOptimality(const Matrix6d& information) const;
  double maxUncertainty() const { return 6.0 / config_.eigenvalue_floor; }

  // J = [ p x n ; n ] for a point p relative to the base origin and a normal n in the same axes
  // (world axes in the paper: p = R_WB p_k, n = n_k).
  static Vector6d pointToPlaneJacobian(const Eigen::Vector3d& p, const Eigen::Vector3d& n);

  // The ray grid in the LiDAR frame (unit vectors), azimuth-major.
  const std::vector<Eigen::Vector3d>& raysLidar() const { return rays_L_; }
  const Config& config() const { return config_; }

 private:
  struct RayTable;
  struct PixelJacobians;
  RayTable rayTable(const PanoramicDepthMap& map) const;
  // Lambda at theta_start + s * step, s = 0 .. count - 1.
  std::vector<Matrix6d> informationSamples(const PanoramicDepthMap& map, DepthMapNormals& normals, double theta_start,
                                           double step, int count) const;
  double rayWeight(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;
  std::int32_t resolve(const PanoramicDepthMap& map, DepthMapNormals& normals, int u, int v,
                       PixelJacobians& pixels) const;

  Config config_;
  std::vector<Eigen::Vector3d> rays_L_;
  // R_BM(theta) is a rotation about the base z axis, so it leaves a ray's elevation unchanged and
  // adds theta to its azimuth. Both are precomputed at theta = 0 (d_B = R_ML d_L): evaluating a
  // candidate angle then needs no trigonometry at all.
  std::vector<double> ray_azimuth_at_zero_;
  std::vector<double> ray_elevation_;
};

}  // namespace uampc::mpc
