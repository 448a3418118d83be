#include "uampc/lo/normal_equations.hpp"

namespace uampc::lo {

void linearise(const std::vector<Correspondence>& correspondences, const BaseState& x,
               const FrameDeviation* deviation, Linearisation& out) {
  const auto count = static_cast<Eigen::Index>(correspondences.size());
  const Eigen::Index basis = deviation ? 15 : 12;
  out.rows.resize(count, basis + 1);
  out.z.resize(count);
  const FrameDeskew deskew(x, deviation);
  const Eigen::Matrix3d R_BW = x.R_WB.transpose();
  for (Eigen::Index i = 0; i < count; ++i) {
    const Correspondence& c = correspondences[static_cast<std::size_t>(i)];
    const TimedPoint& point = *c.point;
    const Eigen::Vector3d& n = c.plane.normal;
    const FrameDeskew::Rotation E = deskew.rotation(point.tau);  // deskew rotation, Exp(w tau)
    const Eigen::Vector3d s = E * point.p_B;                      // point in B at the scan end
    const Eigen::Vector3d q = x.R_WB * s + x.r_WB + deskew.translation(point.tau);
    const Eigen::Vector3d n_B = R_BW * n;
    const Eigen::Vector3d p_x_n = point.p_B.cross(E.transposeTimes(n_B));
    const double z = n.dot(q) + c.plane.offset;  // residual
    out.z(i) = z;
    auto row = out.rows.row(i);
    row.segment<3>(0) = s.cross(n_B).transpose();       // rotation (right)
    row.segment<3>(3) = n.transpose();                  // position
    row.segment<3>(6) = point.tau * n.transpose();      // linear velocity
    row.segment<3>(9) = point.tau * p_x_n.transpose();  // angular velocity
    if (deviation) row.segment<3>(12) = p_x_n.transpose();
    row(basis) = z;
  }
}

NormalEquations normalEquations(Linearisation& linearisation, const FrameDeviation* deviation, double gate) {
  NormalEquations n;
  auto& rows = linearisation.rows;
  n.used = static_cast<std::size_t>(rows.rows());
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    if (beyondGate(linearisation.z(i), gate)) {
      rows.row(i).setZero();
      --n.used;
    }
  }
  // [G z]^T [G z] through a symmetric rank update: half the work of the general product.
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(rows.cols(), rows.cols());
  gram.selfadjointView<Eigen::Upper>().rankUpdate(rows.transpose());
  gram.triangularView<Eigen::StrictlyLower>() = gram.transpose();
  if (!deviation) {
    n.HtH = gram.topLeftCorner<12, 12>();
    n.Htz = gram.topRightCorner<12, 1>();
    return n;
  }
  // H = G T: the state's 12 columns are g's first 12; the deviation's are
  // (tau - tau_mid) n = tau n - tau_mid n and (tau - tau_mid) c = tau c - tau_mid c.
  Eigen::Matrix<double, 15, 18> T = Eigen::Matrix<double, 15, 18>::Zero();
  T.topLeftCorner<12, 12>().setIdentity();
  const double tau_mid = deviation->tau_mid;
  T.block<3, 3>(6, 12).setIdentity();
  T.block<3, 3>(3, 12) = -tau_mid * Eigen::Matrix3d::Identity();
  T.block<3, 3>(9, 15).setIdentity();
  T.block<3, 3>(12, 15) = -tau_mid * Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 15, 15> GtG = gram.topLeftCorner<15, 15>();
  const Eigen::Matrix<double, 18, 18> HtH = T.transpose() * GtG * T;
  const Eigen::Matrix<double, 18, 1> Htz = T.transpose() * gram.topRightCorner<15, 1>();
  n.HtH = GtG.topLeftCorner<12, 12>();
  n.Htz = Htz.head<12>();
  n.HtHe = HtH.topRightCorner<12, 6>();
  n.Hee = HtH.bottomRightCorner<6, 6>();
  n.Hez = Htz.tail<6>();
  return n;
}

}  // namespace uampc::lo
