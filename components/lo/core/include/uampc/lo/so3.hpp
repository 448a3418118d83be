// The few SO(3) maps the filter needs: hat, Exp, Log and the right Jacobian.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace uampc::lo {

inline Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Rodrigues: Exp(phi) = I + sin(a)/a K + (1 - cos(a))/a^2 K^2, K = hat(phi), a = |phi|.
// Below 0.25 rad (every deskew and prediction step) the two coefficients come from their
// series, accurate to 1e-12, which is several times cheaper than sincos.
inline void expSO3Coefficients(double a2, double& s, double& c) {  // a2 = a^2
  if (a2 < 0.0625) {
    s = 1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0 * (1.0 - a2 / 72.0)));
    c = 0.5 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0 * (1.0 - a2 / 90.0))));
  } else {
    const double a = std::sqrt(a2);
    s = std::sin(a) / a;
    c = (1.0 - std::cos(a)) / a2;
  }
}

inline Eigen::Matrix3d expSO3(const Eigen::Vector3d& phi) {
  double s, c;  // sin(a)/a, (1 - cos(a))/a^2
  expSO3Coefficients(phi.squaredNorm(), s, c);
  const Eigen::Matrix3d K = hat(phi);
  return Eigen::Matrix3d::Identity() + s * K + c * K * K;
}

// Exp(phi) kept in Rodrigues form, for rotating a vector or two: v + s phi x v + c phi x (phi x v)
// is two cross products, where forming the matrix costs two 3x3 products. The deskew rotation of
// every point in every iteration is one of these.
class ExpSO3 {
 public:
  explicit ExpSO3(const Eigen::Vector3d& phi) : phi_(phi) {
    expSO3Coefficients(phi.squaredNorm(), s_, c_);
  }
  // Exp(phi) v.
  Eigen::Vector3d operator*(const Eigen::Vector3d& v) const {
    const Eigen::Vector3d pv = phi_.cross(v);
    return v + s_ * pv + c_ * phi_.cross(pv);
  }
  // Exp(phi)^T v = Exp(-phi) v.
  Eigen::Vector3d transposeTimes(const Eigen::Vector3d& v) const {
    const Eigen::Vector3d pv = phi_.cross(v);
    return v - s_ * pv + c_ * phi_.cross(pv);
  }

 private:
  Eigen::Vector3d phi_;
  double s_, c_;
};

inline Eigen::Vector3d logSO3(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

// J_r(phi): Exp(phi + d) ~= Exp(phi) Exp(J_r(phi) d) for small d.
inline Eigen::Matrix3d rightJacobianSO3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  const Eigen::Matrix3d K = hat(phi);
  if (angle < 1e-6) return Eigen::Matrix3d::Identity() - 0.5 * K;
  const double a2 = angle * angle;
  return Eigen::Matrix3d::Identity() - (1.0 - std::cos(angle)) / a2 * K +
         (angle - std::sin(angle)) / (a2 * angle) * K * K;
}

}  // namespace uampc::lo
