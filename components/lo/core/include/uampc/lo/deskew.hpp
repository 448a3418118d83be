// Deskew: ego motion of the base during a frame, from a constant-velocity model.
//
// Each point is placed with the base pose at its own time (not its index):
//   T_WB(t_end + tau) = ( R_WB Exp(w_B tau),  r_WB + v_W tau )
// which is the outer part of Eq. 1 with the base pose interpolated by the motion model.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "uampc/lo/scan.hpp"
#include "uampc/lo/so3.hpp"

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

// The frame's own velocity, where it may differ from the filter's constant velocity
// (OdometryConfig::frame_velocity_std_linear and _angular): the base moves with the state's
// velocity up to the frame's middle, and with the state's velocity plus this deviation within
// the frame, about its middle:
//   T_WB(tau) = ( R_WB Exp(w_B tau_mid) Exp((w_B + dw_B)(tau - tau_mid)),
//                 r_WB + v_W tau + dv_W (tau - tau_mid) ).
struct FrameDeviation {
  double tau_mid = 0.0;                              // s, relative to the state's time
  Eigen::Vector3d dv_W = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d dw_B = Eigen::Vector3d::Zero();  // rad/s
};

// How a frame's points are placed at a state: each with the base pose at its own time, from the
// state's constant velocity, and the frame's deviation from it when there is one.
class FrameDeskew {
 public:
  // The base's rotation from the state's time to a point's, E = Exp(w tau) (or the product of
  // the two above), kept in Rodrigues form.
  class Rotation {
   public:
    Rotation(const ExpSO3* to_middle, const Eigen::Vector3d& phi) : to_middle_(to_middle), within_(phi) {}
    Eigen::Vector3d operator*(const Eigen::Vector3d& v) const {
      const Eigen::Vector3d u = within_ * v;
      return to_middle_ ? *to_middle_ * u : u;
    }
    Eigen::Vector3d transposeTimes(const Eigen::Vector3d& v) const {
      return within_.transposeTimes(to_middle_ ? to_middle_->transposeTimes(v) : v);
    }

   private:
    const ExpSO3* to_middle_;  // null without a deviation
    ExpSO3 within_;
  };

  // deviation may be null (the frame moves with the state's velocity); it must outlive this.
  explicit FrameDeskew(const BaseState& state, const FrameDeviation* deviation = nullptr);

  // Inline: called for every point in every iteration of the update.
  Rotation rotation(double tau) const {
    if (!deviation_) return Rotation(nullptr, state_.w_B * tau);
    return Rotation(&to_middle_, (state_.w_B + deviation_->dw_B) * (tau - deviation_->tau_mid));
  }
  Eigen::Vector3d translation(double tau) const {  // r_WB(tau) - r_WB
    if (!deviation_) return state_.v_W * tau;
    return state_.v_W * tau + deviation_->dv_W * (tau - deviation_->tau_mid);
  }
  // The point in the world frame (Eq. 1, outer part, with T_WB at the point's own time), and the
  // base origin at the point's time.
  Eigen::Vector3d toWorld(const TimedPoint& point) const {
    return state_.R_WB * (rotation(point.tau) * point.p_B) + state_.r_WB + translation(point.tau);
  }
  Eigen::Vector3d originAt(double tau) const { return state_.r_WB + translation(tau); }

 private:
  const BaseState& state_;
  const FrameDeviation* deviation_;
  ExpSO3 to_middle_;  // Exp(w tau_mid)
};

// Every point moved to the world frame with the base pose at its own time.
std::vector<Eigen::Vector3d> deskewToWorld(const std::vector<TimedPoint>& points, const BaseState& state,
                                           const FrameDeviation* deviation = nullptr);

// The middle of the points' time span, (earliest + latest) / 2; 0 for no points.
double middleTime(const std::vector<TimedPoint>& points);

// Which time places a point in the deskew. kTime: its own (the driver's per-point time; ours).
// kIndex: its place in the frame, spread evenly from the previous scan's end to this one's, as
// I2EKF-LO does with the reference simulator's frames, whose points carry index-made times
// (its preprocess gives point i the time i * 1e-9 ms and its deskew interpolates between the two
// poses by that share); a snapshot frame then comes out distorted by the motion since the last
// scan. kNone: every point at the scan's end.
enum class DeskewMode { kTime, kIndex, kNone };

// The points' tau set as `mode` says; since_previous_scan (s) is the time from the previous
// scan's end to this one's (kIndex only; <= 0 for the first scan: every tau 0). The points stay in
// the order the frame delivered them.
void retimeForDeskew(std::vector<TimedPoint>& points, DeskewMode mode, double since_previous_scan);

}  // namespace uampc::lo
