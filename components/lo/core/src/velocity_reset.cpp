#include "uampc/lo/velocity_reset.hpp"

#include "uampc/lo/so3.hpp"

namespace uampc::lo {

void AcceptedPoses::add(double time, const BaseState& state) {
  poses_.push_back({time, state.R_WB, state.r_WB});
  while (poses_.size() > 2 && poses_[1].time <= time - window_) poses_.pop_front();
}

std::optional<Motion> AcceptedPoses::meanMotion() const {
  if (poses_.size() < 2) return std::nullopt;
  // add() keeps the newest pose at or before the window's start: the motion spans the window.
  const Stamped& last = poses_.back();
  const Stamped& first = poses_.front();
  const double dt = last.time - first.time;
  if (!(dt >= 0.01)) return std::nullopt;
  Motion motion;
  motion.v_W = (last.r_WB - first.r_WB) / dt;
  // R_last = R_first Exp(w dt) for a constant body rate w.
  motion.w_B = logSO3(first.R_WB.transpose() * last.R_WB) / dt;
  return motion;
}

IteratedEkf withVelocity(const IteratedEkf& filter, const Motion& motion, std::optional<double> variance) {
  BaseState state = filter.state();
  state.v_W = motion.v_W;
  state.w_B = motion.w_B;
  Matrix12d P = filter.covariance();
  const Matrix6d velocity = P.bottomRightCorner<6, 6>();
  P.topRightCorner<6, 6>().setZero();
  P.bottomLeftCorner<6, 6>().setZero();
  P.bottomRightCorner<6, 6>() = variance ? Matrix6d(*variance * Matrix6d::Identity()) : Matrix6d(velocity.diagonal().asDiagonal());
  return IteratedEkf(state, P);
}

bool beyondSpeedLimits(const BaseState& state, double max_speed, double max_angular_speed) {
  return state.v_W.norm() > max_speed || state.w_B.norm() > max_angular_speed;
}

}  // namespace uampc::lo
