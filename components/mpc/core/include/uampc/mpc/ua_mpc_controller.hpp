// UA-MPC behind one Config and one verb (docs/dev/architecture.md section 1).
//
// One control step: render the panoramic depth map of the local map around the base (Eq. 5),
// sample U over one turn from the current motor angle (U_s = U(theta_now + s * delta_theta)),
// build the periodic piecewise-linear surrogate (Eqs. 9, 10), solve the MPC on it with Ceres and
// return the first speed of the plan. The baselines of the paper are other modes of the same
// controller: constant speed and zero speed.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "uampc/mpc/depth_map_normals.hpp"
#include "uampc/mpc/motor_mpc.hpp"
#include "uampc/mpc/panoramic_depth_map.hpp"
#include "uampc/mpc/uncertainty_filter.hpp"
#include "uampc/mpc/uncertainty_model.hpp"

namespace uampc::mpc {

enum class Mode { kUaMpc, kConstant, kZero };

// "ua_mpc", "constant", "zero".
const char* modeName(Mode mode);
// Throws std::invalid_argument naming the accepted values on an unknown name.
Mode parseMode(const std::string& name);

class UaMpcController {
 public:
  struct Config {
    Mode mode = Mode::kUaMpc;
    double constant_speed = 3.6;                                // rad/s, for Mode::kConstant
    double sample_step = 5.0 * 3.14159265358979323846 / 180.0;  // rad, delta_theta of the samples;
                                                                // rounded so that a whole turn fits
    bool profile_in_baselines = false;                          // also compute the U samples in constant/zero modes
    // U samples averaged over control steps per motor angle (uncertainty_filter.hpp); 1: each
    // step's own samples, as in the paper.
    double u_filter_weight = 1.0;
    // U's range weighting (uncertainty_model.hpp), set from what the LO and the LiDAR are: the
    // LO's scan voxel (m; 0 leaves uncertainty.range_weight_saturation as given, 0 by default:
    // the paper's equal rays) and the LiDAR's points per frame (Mid-360: 200k/s at 10 Hz).
    double range_weight_voxel = 0.3;
    double lidar_points_per_frame = lidar::nominalPointsPerFrame(lidar::livoxMid360());
    PanoramicDepthMap::Config depth_map;
    DepthMapNormals::Config normals;
    UncertaintyModel::Config uncertainty;
    MotorMpc::Config mpc;
  };

  struct Timings {  // elapsed milliseconds of this step's computation (steady_clock, not sim time)
    double depth_map_ms = 0.0;
    double uncertainty_ms = 0.0;  // normals (computed on demand) and all U samples
    double solve_ms = 0.0;
    double total_ms = 0.0;
  };

  struct Decision {
    double omega = 0.0;  // rad/s, the command to execute now
    Mode mode = Mode::kUaMpc;
    bool local_map_empty = false;  // no local-map point within the depth map's range window
    double sample_start = 0.0;     // theta_now, angle of samples[0]
    double sample_step = 0.0;      // rad, delta_theta actually used (2 pi / samples.size())
    std::vector<double> samples;   // U_s as the MPC used them (filtered if so configured), empty when not computed
    MotorMpc::Plan plan;           // empty unless mode == kUaMpc and the map was not empty
    Timings timings;
  };

  // Throws std::invalid_argument on an invalid configuration.
  UaMpcController();  // default Config
  explicit UaMpcController(const Config& config);

  // T_WB: base pose from the LO; local_map_W: the LO's local map in the world frame; theta_now:
  // encoder angle (rad, multi-turn allowed). With an empty local map, UA-MPC returns omega_pre
  // (clamped to the speed bounds) and sets local_map_empty.
  Decision step(const Eigen::Isometry3d& T_WB, const std::vector<Eigen::Vector3d>& local_map_W, double theta_now);
  // step() on float points (as the LO publishes them), without a double copy.
  Decision stepFloat(const Eigen::Isometry3d& T_WB, const std::vector<Eigen::Vector3f>& local_map_W, double theta_now);

  // The panorama of the last step (for publishing as a 32FC1 image).
  const PanoramicDepthMap& depthMap() const { return depth_map_; }
  const Config& config() const { return config_; }

 private:
  template <class Point>
  Decision stepWith(const Eigen::Isometry3d& T_WB, const std::vector<Point>& local_map_W, double theta_now);

  Config config_;
  int sample_count_;
  PanoramicDepthMap depth_map_;
  DepthMapNormals normals_;
  UncertaintyModel uncertainty_;
  UncertaintyFilter filter_;
  MotorMpc mpc_;
  double last_command_ = MotorMpc::kNoPreviousCommand;  // rad/s, the rate term's reference
};

}  // namespace uampc::mpc
