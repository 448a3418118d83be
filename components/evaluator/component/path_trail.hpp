// A trajectory as a viewer draws it (nav_msgs/Path): the poses of a topic, at most one per
// `spacing` seconds. A long run would make the message grow without end (and be published whole
// every path_period), so at kMaxPoses every other pose is dropped and the spacing doubles: the
// whole path stays drawn, coarser as it grows, within a few hundred kilobytes. For the live viewer
// (docs/user/viewing.md); the evaluator's files keep every pose.
#pragma once

#include <cstddef>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc {

class PathTrail {
 public:
  static constexpr std::size_t kMaxPoses = 2000;

  explicit PathTrail(double spacing_s) : spacing_(Time::fromSeconds(spacing_s)) {}

  void add(const std_msgs::msg::Header& header, const geometry_msgs::msg::Pose& pose) {
    const Time stamp = fromMsg(header.stamp());
    auto& poses = path_.poses();
    if (!poses.empty() && stamp < last_ + spacing_) return;
    geometry_msgs::msg::PoseStamped p;
    p.header(header);
    p.pose(pose);
    poses.push_back(p);
    path_.header(header);  // the latest stamp, the poses' frame
    last_ = stamp;
    if (poses.size() >= kMaxPoses) thin();
  }

  bool empty() const { return path_.poses().empty(); }
  const nav_msgs::msg::Path& path() const { return path_; }

 private:
  // Every other pose goes (the first and the latest stay); new poses come half as often.
  void thin() {
    auto& poses = path_.poses();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (i % 2 == 0 || i + 1 == poses.size()) poses[kept++] = poses[i];
    }
    poses.resize(kept);
    spacing_ = Time{spacing_.ns > 0 ? spacing_.ns * 2 : 1'000'000};  // a 0 spacing becomes 1 ms
  }

  Time spacing_;
  Time last_;
  nav_msgs::msg::Path path_;
};

}  // namespace uampc
