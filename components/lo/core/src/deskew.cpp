#include "uampc/lo/deskew.hpp"

#include "uampc/lo/so3.hpp"

namespace uampc::lo {

Eigen::Isometry3d BaseState::pose() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_WB;
  T.translation() = r_WB;
  return T;
}

Eigen::Isometry3d BaseState::poseAt(double tau) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_WB * expSO3(w_B * tau);
  T.translation() = r_WB + v_W * tau;
  return T;
}

std::vector<Eigen::Vector3d> deskewToWorld(const std::vector<TimedPoint>& points,
                                           const BaseState& state) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const TimedPoint& point : points) {
    // Eq. 1, outer part, with T_WB at the point's own time.
    out.push_back(state.R_WB * (ExpSO3(state.w_B * point.tau) * point.p_B) + state.r_WB +
                  state.v_W * point.tau);
  }
  return out;
}

}  // namespace uampc::lo
