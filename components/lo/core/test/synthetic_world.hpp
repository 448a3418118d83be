// A synthetic world, ray-cast analytically, and a simulated motorized Mid-360-like LiDAR.
// Shared by the tests and the benchmark of the LO core; not part of the library.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/lo/scan.hpp"

namespace uampc::lo::sim {

// Box, possibly yawed. solid = false: a room, seen from inside.
struct Box {
  Eigen::Vector3d center;
  Eigen::Vector3d half_size;
  double yaw = 0.0;
  bool solid = true;
  Eigen::Matrix3d R;  // from yaw

  Box(const Eigen::Vector3d& c, const Eigen::Vector3d& h, double yaw_rad, bool is_solid)
      : center(c),
        half_size(h),
        yaw(yaw_rad),
        solid(is_solid),
        R(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix()) {}
};

// Vertical cylinder from z0 to z1 (its caps are not modelled: pillars go floor to ceiling).
struct Pillar {
  Eigen::Vector2d center;
  double radius = 0.3;
  double z0 = 0.0, z1 = 10.0;
};

// Infinite plane normal . x = offset.
struct InfinitePlane {
  Eigen::Vector3d normal;
  double offset = 0.0;
};

struct World {
  std::vector<Box> boxes;
  std::vector<Pillar> pillars;
  std::vector<InfinitePlane> planes;

  // Distance along the unit ray to the first surface, if any within max_range.
  std::optional<double> cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                             double max_range) const {
    constexpr double kEps = 1e-9;
    double best = max_range;
    bool hit = false;
    auto consider = [&](double t) {
      if (t > kEps && t < best) {
        best = t;
        hit = true;
      }
    };
    for (const Box& b : boxes) {
      const Eigen::Vector3d ol = b.R.transpose() * (o - b.center);
      const Eigen::Vector3d dl = b.R.transpose() * d;
      double t_near = -std::numeric_limits<double>::infinity();
      double t_far = std::numeric_limits<double>::infinity();
      bool miss = false;
      for (int a = 0; a < 3; ++a) {
        if (std::abs(dl[a]) < 1e-12) {
          if (std::abs(ol[a]) > b.half_size[a]) miss = true;
          continue;
        }
        double t1 = (-b.half_size[a] - ol[a]) / dl[a];
        double t2 = (b.half_size[a] - ol[a]) / dl[a];
        if (t1 > t2) std::swap(t1, t2);
        t_near = std::max(t_near, t1);
        t_far = std::min(t_far, t2);
      }
      if (miss || t_near > t_far) continue;
      consider(b.solid ? t_near : t_far);
    }
    for (const Pillar& p : pillars) {
      const Eigen::Vector2d oc = o.head<2>() - p.center;
      const Eigen::Vector2d dxy = d.head<2>();
      const double a = dxy.squaredNorm();
      if (a < 1e-12) continue;
      const double bq = 2.0 * oc.dot(dxy);
      const double c = oc.squaredNorm() - p.radius * p.radius;
      const double disc = bq * bq - 4.0 * a * c;
      if (disc < 0.0) continue;
      const double t = (-bq - std::sqrt(disc)) / (2.0 * a);
      const double z = o.z() + t * d.z();
      if (z >= p.z0 && z <= p.z1) consider(t);
    }
    for (const InfinitePlane& pl : planes) {
      const double denominator = pl.normal.dot(d);
      if (std::abs(denominator) < 1e-12) continue;
      consider((pl.offset - pl.normal.dot(o)) / denominator);
    }
    if (!hit) return std::nullopt;
    return best;
  }
};

// A box room with boxes and pillars: every direction constrained.
inline World featureRoom() {
  World w;
  w.boxes.push_back(Box({5, 0, 3}, {15, 9, 3}, 0.0, false));
  w.boxes.push_back(Box({4, 5, 0.75}, {1.0, 0.8, 0.75}, 0.3, true));
  w.boxes.push_back(Box({-3, -4, 1.0}, {0.7, 1.2, 1.0}, -0.5, true));
  w.boxes.push_back(Box({12, -3, 0.5}, {1.5, 0.5, 0.5}, 0.9, true));
  w.boxes.push_back(Box({9, 6, 1.5}, {0.5, 0.5, 1.5}, 0.2, true));
  w.pillars.push_back({{2, -2}, 0.3, 0.0, 6.0});
  w.pillars.push_back({{8, 2.5}, 0.4, 0.0, 6.0});
  w.pillars.push_back({{-5, 3}, 0.25, 0.0, 6.0});
  return w;
}

// A long hall (x from -10 to 110 m) with boxes and pillars scattered along it.
inline World featureHall(unsigned seed = 7) {
  World w;
  w.boxes.push_back(Box({50, 0, 4}, {60, 12, 4}, 0.0, false));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double x = -6.0; x < 106.0; x += 4.0) {
    const double side = (static_cast<int>(x / 4.0) % 2 == 0) ? 1.0 : -1.0;
    w.boxes.push_back(Box({x + 2.0 * u(rng), side * (5.0 + 4.0 * u(rng)), 0.0},
                          {0.4 + u(rng), 0.4 + u(rng), 0.5 + 2.0 * u(rng)}, 3.0 * u(rng), true));
    w.pillars.push_back(
        {{x + 2.0 + 2.0 * u(rng), -side * (4.0 + 3.0 * u(rng))}, 0.2 + 0.3 * u(rng), 0.0, 8.0});
  }
  return w;
}

// A corridor along x, open at both ends: translation along x is unobservable.
inline World corridor() {
  World w;
  w.planes.push_back({Eigen::Vector3d::UnitY(), 2.0});
  w.planes.push_back({Eigen::Vector3d::UnitY(), -2.0});
  w.planes.push_back({Eigen::Vector3d::UnitZ(), 0.0});
  w.planes.push_back({Eigen::Vector3d::UnitZ(), 3.0});
  return w;
}

// Flat ground and nothing else: x, y and yaw are unobservable.
inline World openField() {
  World w;
  w.planes.push_back({Eigen::Vector3d::UnitZ(), 0.0});
  return w;
}

using Trajectory = std::function<Eigen::Isometry3d(double)>;

// Rests at start for `rest` s (the first scan, which starts the map, is taken at rest), then
// speeds up smoothly to `speed` along +x over `ramp` s, weaving sideways, with a little roll and
// pitch; yaw follows the heading.
inline Trajectory weavingTrajectory(const Eigen::Vector3d& start, double speed, double ramp = 1.0,
                                    double weave_amplitude = 1.0, double weave_length = 15.0,
                                    double rest = 0.2) {
  return [=](double time) {
    const double t = time - rest;
    const double k = 2.0 * M_PI / weave_length;
    double x;
    double ramp_factor;
    if (t <= 0.0) {
      x = 0.0;
      ramp_factor = 0.0;
    } else if (t < ramp) {
      x = 0.5 * speed * (t - ramp / M_PI * std::sin(M_PI * t / ramp));
      ramp_factor = 0.5 * (1.0 - std::cos(M_PI * t / ramp));
    } else {
      x = 0.5 * speed * ramp + speed * (t - ramp);
      ramp_factor = 1.0;
    }
    const double y = weave_amplitude * std::sin(k * x);
    const double z = 0.2 * std::sin(x / 7.0);
    const double yaw = std::atan(weave_amplitude * k * std::cos(k * x));
    const double roll = 0.04 * std::sin(0.9 * t) * ramp_factor;
    const double pitch = 0.03 * std::sin(0.6 * t + 1.0) * ramp_factor;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = start + Eigen::Vector3d(x, y, z);
    return T;
  };
}

// Stands at `position` and turns about z the way a hand-held rig does: at rest for `rest` s, the
// yaw rate rises to peak_rate (rad/s) within `ramp` s, holds for `hold` s, falls back to zero
// within `ramp` s and stays there. Cosine ramps, so the rate is continuous but the angular
// acceleration is large (72 deg/s reached or lost within 0.2 s, as in the MCD KTH sequence).
inline Trajectory handheldTurn(const Eigen::Vector3d& position, double peak_rate, double rest = 0.5,
                               double ramp = 0.2, double hold = 0.8) {
  // Integral of 0.5 (1 - cos(pi u / ramp)) over [0, u].
  const auto rising = [ramp](double u) { return 0.5 * (u - ramp / M_PI * std::sin(M_PI * u / ramp)); };
  return [=](double time) {
    const double t = time - rest;
    double yaw = 0.0;  // in units of peak_rate * s
    if (t > 0.0) yaw += rising(std::min(t, ramp));
    if (t > ramp) yaw += std::min(t - ramp, hold);
    if (t > ramp + hold) {  // the falling ramp 0.5 (1 + cos(pi u / ramp)) integrates to u - rising(u)
      const double u = std::min(t - ramp - hold, ramp);
      yaw += u - rising(u);
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(peak_rate * yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = position;
    return T;
  };
}

struct LidarModel {
  frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
  int points_per_frame = 20000;
  double frame_duration = 0.1;  // s
  double min_elevation = -7.0 * M_PI / 180.0;
  double max_elevation = 52.0 * M_PI / 180.0;
  double min_range = 1.5, max_range = 40.0;  // m
  double omega = 3.6;                        // rad/s, motor speed
  double range_noise = 0.0;                  // m, standard deviation
};

inline double motorAngle(const LidarModel& lidar, double t) { return lidar.omega * t; }

// Encoder readings at 200 Hz from t0 to t1 (inclusive-ish), appended to the track.
inline void feedMotor(frames::MotorAngleTrack& track, const LidarModel& lidar, double t0,
                      double t1) {
  const double period = 0.005;
  for (long i = static_cast<long>(std::floor(t0 / period)); i * period <= t1 + period; ++i) {
    const double t = i * period;
    track.add({t, motorAngle(lidar, t), lidar.omega});
  }
}

struct SimulatedScan {
  Scan scan;
  std::vector<Eigen::Vector3d> hits_W;  // ground truth world point of each scan point
};

// Every point cast at its own time: base pose, motor angle and calibration all at t_i (Eq. 1).
// A non-repetitive pattern: a low-discrepancy sequence over the field of view that moves on
// from frame to frame (frame_index).
inline SimulatedScan simulateScan(const World& world, const Trajectory& T_WB,
                                  const LidarModel& lidar, double stamp, long frame_index,
                                  unsigned noise_seed = 1) {
  SimulatedScan out;
  out.scan.stamp = stamp;
  out.scan.points_L.reserve(lidar.points_per_frame);
  out.scan.time_offsets.reserve(lidar.points_per_frame);
  std::mt19937 rng(noise_seed + static_cast<unsigned>(frame_index));
  std::normal_distribution<double> noise(0.0, lidar.range_noise);
  const double golden = 0.6180339887498949;
  const double plastic = 0.7548776662466927;
  const double z0 = std::sin(lidar.min_elevation), z1 = std::sin(lidar.max_elevation);
  for (int i = 0; i < lidar.points_per_frame; ++i) {
    const long n = frame_index * lidar.points_per_frame + i;
    const double azimuth = 2.0 * M_PI * std::fmod(n * golden, 1.0);
    const double sin_elevation = z0 + (z1 - z0) * std::fmod(n * plastic, 1.0);
    const double cos_elevation = std::sqrt(1.0 - sin_elevation * sin_elevation);
    const Eigen::Vector3d d_L(cos_elevation * std::cos(azimuth), cos_elevation * std::sin(azimuth),
                              sin_elevation);
    const double offset = lidar.frame_duration * i / lidar.points_per_frame;
    const double t = stamp + offset;
    const Eigen::Isometry3d T_WL =
        T_WB(t) * frames::lidarPoseInBase(motorAngle(lidar, t), lidar.calibration);
    const Eigen::Vector3d d_W = T_WL.linear() * d_L;
    const std::optional<double> range = world.cast(T_WL.translation(), d_W, lidar.max_range);
    if (!range || *range < lidar.min_range) continue;
    const double measured = *range + (lidar.range_noise > 0.0 ? noise(rng) : 0.0);
    out.scan.points_L.push_back((measured * d_L).cast<float>());
    out.scan.time_offsets.push_back(static_cast<float>(offset));
    out.hits_W.push_back(T_WL.translation() + *range * d_W);
  }
  return out;
}

}  // namespace uampc::lo::sim
