// Which directions of the state a scan's point-to-plane measurements do not constrain, and the
// projection that takes the measurements' information out of those directions.
//
// Zhang, Kaess and Singh, "On Degeneracy of Optimization-based State Estimation Problems"
// (ICRA 2016): the eigenvectors of the information J^T J whose eigenvalues fall below a threshold
// span the degenerate directions; the measurements are not allowed to move the estimate along
// them ("solution remapping"). In our iterated EKF the remapping is done on the linearised
// measurements themselves, H' = H Pi, so that the motion prior alone decides those directions and
// their covariance keeps growing as the prior's does (docs/results/lo-degenerate-geometry.md).
//
// Why the velocities are analysed with the pose. The measurement model deskews each point with
// the velocity (tau v, tau w), so a scan observes velocity too, through the spread of its points'
// times. A surface seen at one instant of the frame (the LiDAR sweeps its azimuth over the frame)
// constrains only yaw + tau w_z: the pose alone looks constrained, but the split between yaw and
// yaw rate is not, and noise then drives the yaw rate (campus poor row: 0 to 0.9 rad/s in 0.6 s
// while the yaw error was still under a degree; docs/results/lo-degenerate-geometry.md, "The
// mechanism"). The joint 12-dimensional information has that direction as a small eigenvalue.
//
// Units. The information mixes rotation (rows s x n, in m), translation (rows n, unitless) and
// velocities (the same rows times tau). Its eigen-decomposition is only meaningful in common
// units, so every component is expressed as a displacement: rotation at a lever arm of `length`
// metres, velocities over `period` seconds (a frame). In those units an eigenvalue is an effective
// number of points: one point on a plane facing the direction squarely counts 1.
#pragma once

#include <Eigen/Core>

namespace uampc::lo {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

// The scales: state component k in displacement units is x_k / scale_k.
struct DegeneracyScales {
  double length = 10.0;  // m, lever arm of a rotation
  double period = 0.1;   // s, time over which a velocity is a displacement
};

template <int N>
struct DegeneracyAnalysis {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  // Eigenvalues of the scaled information, ascending, and their unit eigenvectors (columns) in
  // scaled coordinates (displacements, m).
  Vector eigenvalues = Vector::Zero();
  Matrix eigenvectors = Matrix::Identity();
  int degenerate_directions = 0;  // the first this many eigenvectors are degenerate
  // Pi (unscaled): a state perturbation with its degenerate components removed. Identity when
  // nothing is degenerate.
  Matrix projector = Matrix::Identity();
};
using PoseDegeneracy = DegeneracyAnalysis<6>;
using StateDegeneracy = DegeneracyAnalysis<12>;

// information: unit-weight Lambda = sum_i J_i J_i^T, order [rotation, translation] (pose) or the
// filter's error state [rotation, position, linear velocity, angular velocity] (state).
PoseDegeneracy analysePoseDegeneracy(const Matrix6d& information, const DegeneracyScales& scales, double threshold);
StateDegeneracy analyseStateDegeneracy(const Matrix12d& information, const DegeneracyScales& scales, double threshold);

}  // namespace uampc::lo
