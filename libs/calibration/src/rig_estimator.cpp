#include "uampc/calibration/rig_estimator.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "uampc/calibration/rig_model.hpp"

namespace uampc::calibration {
namespace {

constexpr double kDeg = 180.0 / M_PI;

// A point against its neighbours' plane, every point de-rotated with the candidate (Eq. 1): the
// plane moves with the calibration as the point does.
struct PlaneTermCost {
  const std::vector<CalibrationPoint>* points;
  PlaneTerm term;
  GaugeRig gauge;

  template <typename T>
  bool operator()(const T* rotation, const T* offset, const T* time_offset, T* residual) const {
    using Vector = Eigen::Matrix<T, 3, 1>;
    Vector mean = Vector::Zero();
    for (const auto j : term.neighbours) mean += pointInBase((*points)[j], rotation, offset, time_offset, gauge);
    mean /= T(static_cast<double>(term.neighbours.size()));
    const Vector p = pointInBase((*points)[term.point], rotation, offset, time_offset, gauge);
    residual[0] = term.normal.cast<T>().dot(p - mean);
    return true;
  }
};

frames::MotorAngleTrack encoderTrack(const RigRecording& recording) {
  frames::MotorAngleTrack track(1e12);  // keeps every reading
  for (const auto& reading : recording.encoder) track.add(reading);
  return track;
}

// Points taken evenly from every scan (every k-th of those in range), with the encoder's angle at
// their time plus the believed clock offset. A point whose time the encoder does not cover by
// 50 ms on both sides is left out, so that a changed clock offset still finds an angle.
std::vector<CalibrationPoint> samplePoints(const RigRecording& recording, const frames::MotorAngleTrack& encoder,
                                           const EstimatorConfig& config) {
  std::size_t total = 0;
  for (const auto& scan : recording.scans) total += scan.points.size();
  const std::size_t stride = std::max<std::size_t>(1, total / std::max<std::size_t>(1, config.max_points));
  std::vector<CalibrationPoint> points;
  std::size_t index = 0;
  for (const auto& scan : recording.scans) {
    for (std::size_t i = 0; i < scan.points.size(); ++i, ++index) {
      if (index % stride != 0) continue;
      const Eigen::Vector3d p = scan.points[i].cast<double>();
      const double range = p.norm();
      const double t = scan.stamp + (i < scan.time_offsets.size() ? scan.time_offsets[i] : 0.0);
      if (!p.allFinite() || !std::isfinite(t) || range < config.min_range || range > config.max_range) continue;
      if (!encoder.covers(t - 0.05, t + 0.05)) continue;
      points.push_back({p, t, 0.0, 0.0});
    }
  }
  return points;
}

double rateSpread(const std::vector<CalibrationPoint>& points) {
  double sum = 0.0, squares = 0.0;
  for (const auto& p : points) {
    sum += p.omega;
    squares += p.omega * p.omega;
  }
  const double n = static_cast<double>(points.size());
  return std::sqrt(std::max(0.0, squares / n - (sum / n) * (sum / n)));
}

struct MapState {
  std::vector<Eigen::Vector3d> positions;
  std::vector<double> angles;
};

MapState deRotate(const std::vector<CalibrationPoint>& points, const ObservableRig& x, const GaugeRig& gauge) {
  MapState map;
  map.positions.reserve(points.size());
  map.angles.reserve(points.size());
  for (const auto& p : points) {
    map.positions.push_back(pointInBase(p, x.rotation, x.offset, x.time_offset, gauge));
    map.angles.push_back(rotorAngle(p, x, gauge));
  }
  return map;
}

std::vector<double> distancesOf(const std::vector<PlaneTerm>& terms, const std::vector<Eigen::Vector3d>& positions) {
  std::vector<double> d;
  d.reserve(terms.size());
  for (const auto& term : terms) d.push_back(planeDistance(term, positions));
  return d;
}

// The q-quantile of the values' magnitudes (0.5: the median).
double quantileAbsolute(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  for (auto& v : values) v = std::abs(v);
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

double medianAbsolute(const std::vector<double>& values) { return quantileAbsolute(values, 0.5); }

// One Ceres problem over the terms, each with a Huber loss; the clock offset held unless asked.
struct Solve {
  ceres::Problem problem;
  std::size_t residuals = 0;

  Solve(const std::vector<CalibrationPoint>& points, const std::vector<PlaneTerm>& terms, const GaugeRig& gauge,
        ObservableRig& x, bool estimate_time, double huber) {
    for (const auto& term : terms) {
      auto* cost = new ceres::AutoDiffCostFunction<PlaneTermCost, 1, 2, 2, 1>(new PlaneTermCost{&points, term, gauge});
      problem.AddResidualBlock(cost, new ceres::HuberLoss(huber), x.rotation, x.offset, x.time_offset);
      ++residuals;
    }
    if (!estimate_time) problem.SetParameterBlockConstant(x.time_offset);
  }

  ceres::Solver::Summary run(int iterations) {
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = iterations;
    options.num_threads = 1;  // a shared machine; the terms are cheap
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    return summary;
  }
};

struct StandardDeviations {
  double rotation[2] = {0, 0}, offset[2] = {0, 0}, time_offset = 0;
};

// The covariance Ceres finds for the minimum, scaled by the terms' own variance (the robustified
// cost per degree of freedom): the terms' noise is not known beforehand.
StandardDeviations standardDeviations(Solve& solve, ObservableRig& x, bool estimate_time, double final_cost) {
  ceres::Covariance::Options options;
  options.num_threads = 1;
  options.algorithm_type = ceres::DENSE_SVD;  // five parameters: dense is cheap and needs no SuiteSparse
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> blocks = {{x.rotation, x.rotation}, {x.offset, x.offset}};
  if (estimate_time) blocks.emplace_back(x.time_offset, x.time_offset);
  StandardDeviations sd;
  if (!covariance.Compute(blocks, &solve.problem)) {
    sd.rotation[0] = sd.rotation[1] = sd.offset[0] = sd.offset[1] = sd.time_offset = INFINITY;
    return sd;
  }
  const double dof = static_cast<double>(solve.residuals) - (estimate_time ? 5.0 : 4.0);
  const double variance = 2.0 * final_cost / std::max(1.0, dof);
  double c2[4], c1[1];
  covariance.GetCovarianceBlock(x.rotation, x.rotation, c2);
  sd.rotation[0] = std::sqrt(c2[0] * variance);
  sd.rotation[1] = std::sqrt(c2[3] * variance);
  covariance.GetCovarianceBlock(x.offset, x.offset, c2);
  sd.offset[0] = std::sqrt(c2[0] * variance);
  sd.offset[1] = std::sqrt(c2[3] * variance);
  if (estimate_time) {
    covariance.GetCovarianceBlock(x.time_offset, x.time_offset, c1);
    sd.time_offset = std::sqrt(c1[0] * variance);
  }
  return sd;
}

std::vector<ParameterEstimate> report(const frames::MotorLidarCalibration& believed, const ObservableRig& x,
                                      const GaugeRig& gauge, const StandardDeviations& sd, bool estimate_time) {
  const ObservableRig b = observablePart(believed);
  const char* about_axis =
      "a turn about the motor axis turns the whole map; with a still base it cannot be told from the encoder's zero";
  std::vector<ParameterEstimate> p;
  p.push_back({"roll_deg", b.rotation[0] * kDeg, x.rotation[0] * kDeg, sd.rotation[0] * kDeg, true, ""});
  p.push_back({"pitch_deg", b.rotation[1] * kDeg, x.rotation[1] * kDeg, sd.rotation[1] * kDeg, true, ""});
  p.push_back({"yaw_deg", gauge.yaw * kDeg, gauge.yaw * kDeg, 0.0, false, about_axis});
  p.push_back({"x", b.offset[0], x.offset[0], sd.offset[0], true, ""});
  p.push_back({"y", b.offset[1], x.offset[1], sd.offset[1], true, ""});
  p.push_back({"z", gauge.z, gauge.z, 0.0, false, "a shift along the motor axis shifts the whole map"});
  p.push_back({"encoder_offset_deg", gauge.encoder_offset * kDeg, gauge.encoder_offset * kDeg, 0.0, false,
               "it turns the whole map about the motor axis, as yaw does"});
  if (estimate_time) {
    p.push_back({"time_offset", b.time_offset[0], x.time_offset[0], sd.time_offset, true, ""});
  } else {
    p.push_back({"time_offset", b.time_offset[0], b.time_offset[0], 0.0, false,
                 "the motor turned at one speed: an offset in time is then one in angle, a turn of the whole map "
                 "(vary the speed while recording)"});
  }
  return p;
}

// How far the calibrated map's points lie off the planes of points seen at least a third of the
// recording (at most 1 s) earlier or later, m (third quartile): a still base and scene give the
// noise, a base that moved gives its motion, which neighbours of nearby motor angles (seen a
// fraction of a second apart) hardly show; planes along the motion do not show it either, hence
// not the median. Infinite when no such planes are found.
double agreementOverTime(const std::vector<CalibrationPoint>& points, const MapState& map, const PlaneTermConfig& base,
                         double& apart) {
  std::vector<double> times;
  times.reserve(points.size());
  for (const auto& p : points) times.push_back(p.time);
  const auto [first, last] = std::minmax_element(times.begin(), times.end());
  PlaneTermConfig config = base;
  config.min_angle_apart = 0.0;
  config.min_time_apart = apart = std::min(1.0, (*last - *first) / 3.0);
  const std::vector<PlaneTerm> terms = findPlaneTerms(map.positions, map.angles, config, &times);
  if (terms.size() < 10) return INFINITY;
  return quantileAbsolute(distancesOf(terms, map.positions), 0.75);
}

bool converged(const ObservableRig& a, const ObservableRig& b) {
  return std::abs(a.rotation[0] - b.rotation[0]) < 2e-6 && std::abs(a.rotation[1] - b.rotation[1]) < 2e-6 &&
         std::abs(a.offset[0] - b.offset[0]) < 2e-5 && std::abs(a.offset[1] - b.offset[1]) < 2e-5 &&
         std::abs(a.time_offset[0] - b.time_offset[0]) < 2e-6;
}

}  // namespace

std::string millimetres(double metres) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << metres * 1e3 << " mm";
  return s.str();
}

CalibrationResult estimateRig(const RigRecording& recording, const frames::MotorLidarCalibration& believed,
                              const EstimatorConfig& config, const Progress& progress) {
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  if (auto problem = whyNotCalibratable(recording, config.limits)) throw CalibrationError(*problem);
  const frames::MotorAngleTrack encoder = encoderTrack(recording);
  std::vector<CalibrationPoint> points = samplePoints(recording, encoder, config);
  ObservableRig x = observablePart(believed);
  GaugeRig gauge = gaugePart(believed);
  takeEncoderAnglesAt(x.time_offset[0], encoder, points, gauge);
  const bool estimate_time = rateSpread(points) >= config.min_rate_spread;
  say("calibrate: " + std::to_string(points.size()) + " points from " + std::to_string(recording.scans.size()) +
      " scans" + (estimate_time ? "" : "; the motor's speed hardly varied, the clock offset is held"));

  CalibrationResult result;
  result.points = points.size();
  std::vector<PlaneTerm> terms;
  double final_cost = 0.0;
  std::unique_ptr<Solve> solve;
  for (int k = 0; k < config.outer_iterations; ++k) {
    takeEncoderAnglesAt(x.time_offset[0], encoder, points, gauge);
    const MapState map = deRotate(points, x, gauge);
    terms = findPlaneTerms(map.positions, map.angles, config.terms);
    if (terms.size() < config.min_terms) {
      throw CalibrationError("only " + std::to_string(terms.size()) + " planes were found in the map (at least " +
                             std::to_string(config.min_terms) +
                             " are needed): the scene is too featureless or too far, or the calibration too far off");
    }
    const std::vector<double> before = distancesOf(terms, map.positions);
    if (k == 0) result.distances_before = before;
    const ObservableRig previous = x;
    solve = std::make_unique<Solve>(points, terms, gauge, x, estimate_time, config.huber);
    const ceres::Solver::Summary summary = solve->run(config.solver_iterations);
    final_cost = summary.final_cost;
    const MapState moved = deRotate(points, x, gauge);
    say("calibrate: iteration " + std::to_string(k + 1) + "/" + std::to_string(config.outer_iterations) + ": " +
        std::to_string(terms.size()) + " planes, median distance off them " + millimetres(medianAbsolute(before)) +
        " -> " + millimetres(medianAbsolute(distancesOf(terms, moved.positions))));
    result.outer_iterations = k + 1;
    if (k > 0 && converged(previous, x)) break;
  }
  const StandardDeviations sd = standardDeviations(*solve, x, estimate_time, final_cost);
  const MapState final_map = deRotate(points, x, gauge);
  result.distances_after = distancesOf(terms, final_map.positions);
  result.terms = terms.size();
  result.median_distance_before = medianAbsolute(result.distances_before);
  result.median_distance_after = medianAbsolute(result.distances_after);
  double apart = 0.0;
  const double over_time = agreementOverTime(points, final_map, config.terms, apart);
  const double after = quantileAbsolute(result.distances_after, 0.75);
  say("calibrate: a quarter of the points seen " + std::to_string(apart).substr(0, 4) + " s or more apart lie over " +
      (std::isfinite(over_time) ? millimetres(over_time) : std::string("(no planes)")) + " off each other's planes");
  if (std::max(after, over_time) > config.max_off_plane) {
    const double worst = std::max(after, over_time);
    std::ostringstream s;
    s.precision(2);
    s << apart;
    throw CalibrationError("the calibrated map does not agree with itself: a quarter of its points lie over " +
                           (std::isfinite(worst) ? millimetres(worst) : std::string("too far to pair")) +
                           " off the planes of points seen " +
                           (worst == over_time ? s.str() + " s or more" : "at other motor angles") +
                           " apart (at most " + millimetres(config.max_off_plane) +
                           " expected): did the base or the scene move during the recording?");
  }
  result.calibration = assemble(x, gauge);
  result.parameters = report(believed, x, gauge, sd, estimate_time);
  return result;
}

}  // namespace uampc::calibration
