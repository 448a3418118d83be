// A trajectory as a viewer draws it (nav_msgs/Path): the poses of a topic, at most one per
// `spacing` seconds, so that a path of a long run stays a few hundred kilobytes. For the live
// viewer (docs/user/viewing.md); the evaluator's files keep every pose.
#pragma once

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc {

class PathTrail {
 public:
  explicit PathTrail(double spacing_s) : spacing_(Time::fromSeconds(spacing_s)) {}

  void add(const std_msgs::msg::Header& header, const geometry_msgs::msg::Pose& pose) {
    const Time stamp = fromMsg(header.stamp());
    if (!path_.poses().empty() && stamp < last_ + spacing_) return;
    geometry_msgs::msg::PoseStamped p;
    p.header(header);
    p.pose(pose);
    path_.poses().push_back(p);
    path_.header(header);  // the latest stamp, the poses' frame
    last_ = stamp;
  }

  bool empty() const { return path_.poses().empty(); }
  const nav_msgs::msg::Path& path() const { return path_; }

 private:
  Time spacing_;
  Time last_;
  nav_msgs::msg::Path path_;
};

}  // namespace uampc
