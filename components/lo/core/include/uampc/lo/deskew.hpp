// Deskew: ego motion of the base during a frame, from a constant-velocity model.
//
// Each point is placed with the base pose at its own time (not its index):
//   T_WB(t_end + tau) = ( R_WB Exp(w_B tau),  r_WB + v_W tau )
// which is the outer part of Eq. 1 with the base pose interpolated by the motion model.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// Kinematic state of the base at one time: the state of the filter.
struct BaseState {
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r_WB = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();   // m/s, linear velocity in the world frame
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();   // rad/s, angular velocity in the base frame

  Eigen::Isometry3d pose() const;
  // Base pose tau seconds after this state's time, at constant velocity.
  Eigen::Isometry3d poseAt(double tau) const;
};

// Every point moved to the world frame with the base pose at its own time.
std::vector<Eigen::Vector3d> deskewToWorld(const std::vector<TimedPoint>& points,
                                           const BaseState& state);

}  // namespace uampc::lo
