#include "uampc/lo/degeneracy.hpp"

#include <Eigen/Eigenvalues>

namespace uampc::lo {

namespace {

// scale: x_k / scale_k is component k in displacement units (y = S^-1 x, scaled Jacobian H S).
template <int N>
DegeneracyAnalysis<N> analyse(const Eigen::Matrix<double, N, N>& information, const Eigen::Matrix<double, N, 1>& scale,
                              double threshold) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const Matrix scaled = scale.asDiagonal() * information * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(0.5 * (scaled + scaled.transpose()));
  DegeneracyAnalysis<N> analysis;
  analysis.eigenvalues = solver.eigenvalues().cwiseMax(0.0);
  analysis.eigenvectors = solver.eigenvectors();
  while (analysis.degenerate_directions < N && analysis.eigenvalues(analysis.degenerate_directions) < threshold) {
    ++analysis.degenerate_directions;
  }
  if (analysis.degenerate_directions == 0) return analysis;
  // Removing the degenerate components in scaled coordinates, H S (I - V_d V_d^T) S^-1 x, gives
  // the projector in unscaled coordinates.
  const auto degenerate = analysis.eigenvectors.leftCols(analysis.degenerate_directions);
  const Matrix scaled_projector = Matrix::Identity() - degenerate * degenerate.transpose();
  analysis.projector = scale.asDiagonal() * scaled_projector * scale.cwiseInverse().asDiagonal();
  return analysis;
}

}  // namespace

PoseDegeneracy analysePoseDegeneracy(const Matrix6d& information, const DegeneracyScales& scales, double threshold) {
  Vector6d scale;
  scale << Eigen::Vector3d::Constant(1.0 / scales.length), Eigen::Vector3d::Ones();
  return analyse<6>(information, scale, threshold);
}

StateDegeneracy analyseStateDegeneracy(const Matrix12d& information, const DegeneracyScales& scales, double threshold) {
  Vector12d scale;
  scale << Eigen::Vector3d::Constant(1.0 / scales.length), Eigen::Vector3d::Ones(),
      Eigen::Vector3d::Constant(1.0 / scales.period), Eigen::Vector3d::Constant(1.0 / (scales.length * scales.period));
  return analyse<12>(information, scale, threshold);
}

}  // namespace uampc::lo
