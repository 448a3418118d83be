#include "uampc/lo/deskew.hpp"

#include <algorithm>

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

FrameDeskew::FrameDeskew(const BaseState& state, const FrameDeviation* deviation)
    : state_(state),
      deviation_(deviation),
      to_middle_(deviation ? Eigen::Vector3d(state.w_B * deviation->tau_mid) : Eigen::Vector3d::Zero()) {}

std::vector<Eigen::Vector3d> deskewToWorld(const std::vector<TimedPoint>& points, const BaseState& state,
                                           const FrameDeviation* deviation) {
  const FrameDeskew deskew(state, deviation);
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const TimedPoint& point : points) out.push_back(deskew.toWorld(point));
  return out;
}

double middleTime(const std::vector<TimedPoint>& points) {
  if (points.empty()) return 0.0;
  const auto [earliest, latest] = std::minmax_element(
      points.begin(), points.end(), [](const TimedPoint& a, const TimedPoint& b) { return a.tau < b.tau; });
  return 0.5 * (earliest->tau + latest->tau);
}

void retimeForDeskew(std::vector<TimedPoint>& points, DeskewMode mode, double since_previous_scan) {
  if (mode == DeskewMode::kTime) return;
  const bool spread = mode == DeskewMode::kIndex && since_previous_scan > 0.0 && points.size() > 1;
  const double last = static_cast<double>(points.size()) - 1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Point i of N at the share i / (N - 1) of the way from the previous scan's end (tau = -dt)
    // to this one's (tau = 0).
    points[i].tau = spread ? (static_cast<double>(i) / last - 1.0) * since_previous_scan : 0.0;
  }
}

}  // namespace uampc::lo
