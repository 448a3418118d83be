#include "uampc/lo/plane_fit.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace uampc::lo {

namespace {

// Whether the in-plane spreads lambda_1 <= lambda_2 of a scatter matrix have lambda_1 / lambda_2
// below min_ratio, from their sum (trace - lambda_0) and product (the adjugate's trace is
// lambda_0 (lambda_1 + lambda_2) + lambda_1 lambda_2).
bool thin(double in_plane_sum, double adjugate_trace, double lambda_0, double min_ratio) {
  const double product = adjugate_trace - lambda_0 * in_plane_sum;
  const double root = std::sqrt(std::max(0.0, in_plane_sum * in_plane_sum - 4.0 * product));
  const double wider = 0.5 * (in_plane_sum + root), narrower = 0.5 * (in_plane_sum - root);
  return !(narrower >= min_ratio * wider);
}

}  // namespace

// The normal is the eigenvector of the scatter matrix S with the smallest eigenvalue. It is
// taken from the adjugate adj(S) = sum_i (prod_{j != i} lambda_j) v_i v_i^T, which for a planar
// patch (lambda_0 << lambda_1 <= lambda_2) is dominated by v_0 v_0^T: its largest column is
// already close to the normal, and two power-iteration steps on adj(S) (each shrinking the error
// by lambda_0 / lambda_1) make it exact to rounding. No trigonometry, unlike a full 3x3
// eigen-solver, and this runs for every correspondence.
std::optional<Plane> fitPlane(const std::vector<Eigen::Vector3d>& points, double max_point_distance,
                              PlaneSpread* spread, double min_spread_ratio) {
  if (points.size() < 3) return std::nullopt;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - centroid;
    S.noalias() += d * d.transpose();
  }
  // Adjugate of the symmetric S (cofactors).
  Eigen::Matrix3d adj;
  adj(0, 0) = S(1, 1) * S(2, 2) - S(1, 2) * S(1, 2);
  adj(1, 1) = S(0, 0) * S(2, 2) - S(0, 2) * S(0, 2);
  adj(2, 2) = S(0, 0) * S(1, 1) - S(0, 1) * S(0, 1);
  adj(0, 1) = adj(1, 0) = S(0, 2) * S(1, 2) - S(0, 1) * S(2, 2);
  adj(0, 2) = adj(2, 0) = S(0, 1) * S(1, 2) - S(0, 2) * S(1, 1);
  adj(1, 2) = adj(2, 1) = S(0, 1) * S(0, 2) - S(0, 0) * S(1, 2);
  // Collinear (or coincident) points: lambda_0 = lambda_1 = 0, so adj(S) vanishes against
  // trace(S)^2 ~ lambda_2^2; no plane.
  const double trace = S.trace();
  int best = 0;
  adj.diagonal().maxCoeff(&best);
  if (!(adj(best, best) > 1e-10 * trace * trace)) return std::nullopt;
  Eigen::Vector3d normal = adj.col(best).normalized();
  normal = (adj * normal).normalized();
  normal = (adj * normal).normalized();
  if (!normal.allFinite()) return std::nullopt;
  Plane plane;
  plane.normal = normal;
  plane.offset = -normal.dot(centroid);
  const double lambda_0 = std::max(0.0, normal.dot(S * normal));  // spread across the plane
  if (min_spread_ratio > 0.0 && thin(trace - lambda_0, adj.trace(), lambda_0, min_spread_ratio)) return std::nullopt;
  for (const auto& p : points) {
    if (std::abs(normal.dot(p) + plane.offset) > max_point_distance) return std::nullopt;
  }
  if (spread) {
    spread->scatter_variance = points.size() > 3 ? lambda_0 / static_cast<double>(points.size() - 3) : 0.0;
    spread->scatter = {S(0, 0), S(0, 1), S(0, 2), S(1, 1), S(1, 2), S(2, 2)};
  }
  return plane;
}

// The pseudo-inverse of S restricted to the plane, P S P with P = I - n n^T, is
// (P S P + n n^T)^-1 - n n^T: the added n n^T makes it invertible without touching the plane.
Eigen::Matrix3d spreadInverse(const Plane& plane, const PlaneSpread& spread) {
  const auto& s = spread.scatter;
  Eigen::Matrix3d S;
  S << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
  if (S.isZero()) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d nn = plane.normal * plane.normal.transpose();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - nn;
  const Eigen::Matrix3d inverse = (P * S * P + nn).inverse() - nn;
  return inverse.allFinite() ? inverse : Eigen::Matrix3d::Zero();
}

}  // namespace uampc::lo
