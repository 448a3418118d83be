#include "uampc/lo/start_poses.hpp"

namespace uampc::lo {

void StartPoses::add(double time, const Eigen::Isometry3d& T_WB) {
  if (samples_.size() >= kCapacity) samples_.pop_front();
  samples_.push_back({time, T_WB});
}

std::optional<StartState> StartPoses::at(double time) const {
  for (std::size_t i = 1; i < samples_.size(); ++i) {
    const Sample& now = samples_[i];
    if (now.time + 1e-9 < time) continue;
    const Sample& before = samples_[i - 1];
    StartState start;
    start.T_WB = now.T_WB;
    const double dt = now.time - before.time;
    if (dt > 0) {
      start.velocity_W = (now.T_WB.translation() - before.T_WB.translation()) / dt;
      const Eigen::AngleAxisd turn(before.T_WB.linear().transpose() * now.T_WB.linear());
      start.angular_velocity_B = turn.axis() * turn.angle() / dt;
    }
    return start;
  }
  return std::nullopt;
}

}  // namespace uampc::lo
