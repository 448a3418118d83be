// A plane through a few map points, for point-to-plane residuals.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace uampc::lo {

// Points x on the plane satisfy normal.dot(x) + offset = 0; |normal| = 1.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
  // Expected squared tilt of the normal about an in-plane axis (rad^2), from the fit's own
  // scatter: sigma^2 (1 / lambda_1 + 1 / lambda_2) / 2, sigma^2 = lambda_0 / (k - 3) the points'
  // variance across the plane, lambda the scatter matrix's eigenvalues (an isotropic
  // approximation of the normal's covariance). 0 for an exact fit.
  double normal_variance = 0.0;
};

// Least-squares plane (smallest eigenvector of the scatter matrix). Nothing when there are fewer
// than 3 points, they are collinear, or any of them lies more than max_point_distance off the
// fitted plane (the neighbourhood is not planar: an edge, a corner, clutter).
std::optional<Plane> fitPlane(const std::vector<Eigen::Vector3d>& points,
                              double max_point_distance);

}  // namespace uampc::lo
