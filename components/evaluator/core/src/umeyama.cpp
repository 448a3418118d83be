#include "uampc/evaluator/umeyama.hpp"

#include <Eigen/SVD>
#include <stdexcept>
#include <string>

namespace uampc::evaluator {

Eigen::Isometry3d umeyamaAlignment(const std::vector<Eigen::Vector3d>& source,
                                   const std::vector<Eigen::Vector3d>& target) {
  if (source.size() != target.size()) {
    throw std::invalid_argument("umeyamaAlignment: " + std::to_string(source.size()) +
                                " source points but " + std::to_string(target.size()) +
                                " target points");
  }
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  const std::size_t n = source.size();
  if (n == 0) return transform;

  Eigen::Vector3d mean_source = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_target = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_source += source[i];
    mean_target += target[i];
  }
  mean_source /= static_cast<double>(n);
  mean_target /= static_cast<double>(n);

  // Cross-covariance of target and source: Sigma = 1/n sum (t - mu_t)(s - mu_s)^T.
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    sigma += (target[i] - mean_target) * (source[i] - mean_source).transpose();
  }
  sigma /= static_cast<double>(n);

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  // Without the sign, U V^T may be a reflection (det -1) for noisy or planar data.
  Eigen::Vector3d s(1.0, 1.0, (U.determinant() * V.determinant() < 0.0) ? -1.0 : 1.0);
  transform.linear() = U * s.asDiagonal() * V.transpose();
  transform.translation() = mean_target - transform.linear() * mean_source;
  return transform;
}

}  // namespace uampc::evaluator
