// Where the odometry starts: a pose source (ground truth in simulation) sampled at the first
// scan's end, the time the LO's pose refers to, so that the unaligned ATE compares like with like;
// and the velocity there, differentiated from the sample before it, because the first scan is
// deskewed with it. A real robot without such a source starts at identity, at rest.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include <Eigen/Geometry>

namespace uampc::lo {

struct StartState {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();          // m/s; zero when the two samples share a time
  Eigen::Vector3d angular_velocity_B = Eigen::Vector3d::Zero();  // rad/s
};

// The samples of the pose source received before the first scan could be registered.
class StartPoses {
 public:
  // At most this many samples are kept (20 s at 200 Hz), the oldest dropped first.
  static constexpr std::size_t kCapacity = 4001;

  void add(double time, const Eigen::Isometry3d& T_WB);
  // The first sample at or after time (1 ns of tolerance) that has a sample before it, with the
  // velocity from that one to it; nothing until such a sample has arrived.
  std::optional<StartState> at(double time) const;
  void clear() { samples_.clear(); }
  std::size_t size() const { return samples_.size(); }

 private:
  struct Sample {
    double time;
    Eigen::Isometry3d T_WB;
  };
  std::deque<Sample> samples_;
};

}  // namespace uampc::lo
