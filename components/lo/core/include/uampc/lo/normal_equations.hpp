// The point-to-plane measurement model of the iterated EKF (iterated_ekf.hpp) linearised at an
// iterate, and its unit-weight normal equations H^T H and H^T z, summed row by row into
// fixed-size matrices.
//
// The row of H of a point p (time tau) on its plane (n, d) at the iterate x is, with the deskew
// rotation E = Exp(w tau) (or the frame deviation's product), s = E p, n_B = R^T n and
// c = p x E^T n_B (the residual's derivatives, as FAST-LIO2's h_x, extended to the velocities):
//   J = [ s x n_B,  n,  tau n,  tau c ]                                        (12 unknowns)
//   J = [ s x n_B,  n,  tau n,  tau c,  (tau - tau_mid) n,  (tau - tau_mid) c ]  (18, with the
//                                                                   frame's deviation e)
// The deviation's columns are the velocity columns less tau_mid times (n, c), so with e every row
// lies in the span of the 15 numbers g = [s x n_B, n, tau n, tau c, c]: H = G T, T a fixed 15x18
// matrix, and H^T H = T^T (G^T G) T. G with z as one more column gives H^T H and H^T z in one
// symmetric rank update of 16 columns: 136 products a row where H's 18 columns and the separate
// H^T z took 189.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "uampc/lo/degeneracy.hpp"
#include "uampc/lo/deskew.hpp"
#include "uampc/lo/plane_fit.hpp"
#include "uampc/lo/scan.hpp"

namespace uampc::lo {

struct Correspondence {
  const TimedPoint* point;
  Plane plane;
};

// One linearisation: per correspondence its residual z = n^T q + d, and the rows [g, z] (12 + 1
// columns, or 15 + 1 with a frame deviation), row-major so that a row is written contiguously.
struct Linearisation {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows;
  Eigen::VectorXd z;
};

// The unit-weight normal equations of the rows kept: the state's H^T H and H^T z, and with a
// frame deviation its cross terms with the state and its own.
struct NormalEquations {
  Matrix12d HtH = Matrix12d::Zero();
  Vector12d Htz = Vector12d::Zero();
  Eigen::Matrix<double, 12, 6> HtHe = Eigen::Matrix<double, 12, 6>::Zero();
  Matrix6d Hee = Matrix6d::Zero();
  Vector6d Hez = Vector6d::Zero();
  std::size_t used = 0;  // rows within the gate
};

// The measurement model h(x) linearised at x (deviation may be null).
void linearise(const std::vector<Correspondence>& correspondences, const BaseState& x,
               const FrameDeviation* deviation, Linearisation& out);

// Whether a residual is left out by the gate (a wrong plane, see iterated_ekf.hpp).
inline bool beyondGate(double z, double gate) { return std::abs(z) > gate; }

// The normal equations of the rows within the gate (infinity: every row); the rows beyond it are
// zeroed (a zero row adds nothing).
NormalEquations normalEquations(Linearisation& linearisation, const FrameDeviation* deviation, double gate);

}  // namespace uampc::lo
