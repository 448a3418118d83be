// Rigid alignment (SE(3), no scale) of one point set onto another: Umeyama (1991) / Kabsch.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace uampc::evaluator {

// The rigid transform T minimising sum_i ||target_i - T * source_i||^2, so that applying it to the
// estimate, T * source_i, lands on the ground truth. With Sigma = 1/n sum (t_i - mu_t)(s_i -
// mu_s)^T = U D V^T, R = U diag(1, 1, det(U) det(V)) V^T (the sign fixes a reflection) and t = mu_t
// - R mu_s. Not R^T: the reference code applied the transposed rotation. Throws
// std::invalid_argument when the sizes differ. No points give the identity, one point a pure
// translation; collinear points leave the rotation about their line undetermined.
// Why not Eigen::umeyama: it is the same method (the test compares the two to 1e-9), but its
// sums run in another order, which changes the last digits of every aligned ATE that the run
// files print (measured: all of 100 random trajectories differ bitwise).
Eigen::Isometry3d umeyamaAlignment(const std::vector<Eigen::Vector3d>& source,
                                   const std::vector<Eigen::Vector3d>& target);

}  // namespace uampc::evaluator
