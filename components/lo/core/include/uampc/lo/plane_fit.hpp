// A plane through a few map points, for point-to-plane residuals.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

namespace uampc::lo {

// Points x on the plane satisfy normal.dot(x) + offset = 0; |normal| = 1.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};

// How a fit's normal tilts: its covariance is sigma^2 spreadInverse(plane, spread), with sigma^2
// the points' variance across the plane. Apart from Plane, which every correspondence carries
// through the hot loops, so that those stay lean.
struct PlaneSpread {
  // lambda_0 / (k - 3): sigma^2 from this fit alone (0 for an exact fit); a patch that bends over
  // an edge inflates it, so a frame's typical value is the better estimate (see
  // planeNoiseInformation in iterated_ekf.cpp).
  double scatter_variance = 0.0;
  // The fit's scatter matrix S (sum of d d^T about the centroid), upper triangle row by row;
  // spreadInverse() is worked out from it on demand (for a quarter of one association's planes:
  // in every fit it cost 0.7 ms a frame).
  std::array<double, 6> scatter{};
};

// Least-squares plane (smallest eigenvector of the scatter matrix). Nothing when there are fewer
// than 3 points, they are collinear, or any of them lies more than max_point_distance off the
// fitted plane (the neighbourhood is not planar: an edge, a corner, clutter).
// With spread, also how the fit's normal tilts. min_spread_ratio > 0 also rejects thin patches:
// lambda_1 / lambda_2 of the scatter (the in-plane spreads, narrower over wider) below it.
std::optional<Plane> fitPlane(const std::vector<Eigen::Vector3d>& points, double max_point_distance,
                              PlaneSpread* spread = nullptr, double min_spread_ratio = 0.0);

// (S restricted to the plane)^+, m^-2: the shape of the normal's covariance (it tilts least about
// the direction the points spread along most); zero for a plane with no scatter recorded.
Eigen::Matrix3d spreadInverse(const Plane& plane, const PlaneSpread& spread);

}  // namespace uampc::lo
