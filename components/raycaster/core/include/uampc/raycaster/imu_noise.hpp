// Discrete-time IMU noise: white noise plus a bias random walk, per axis, seeded.
//
// The standard continuous model (Kalibr, "IMU Noise Model",
// https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model) sampled at dt = 1 / rate:
//   white noise   n[k]     = noise_density / sqrt(dt) * w[k]
//   bias          b[k + 1] = b[k] + random_walk * sqrt(dt) * w'[k],   b[k0] = 0
// with w, w' independent standard normals and k0 the origin, the sample at the simulation's start
// (0 in lockstep; in real time the first sample at or after the wall-clock time the component
// started, not the Unix epoch's sample 0, which would be ~10^11 steps away: docs/dev/time-and-lockstep.md).
// Sample k draws its numbers from a stream of its own, seeded from (seed, k), so the noise of
// sample k depends only on the seed, the origin and k: not on which samples were asked for before,
// nor how often.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace uampc::raycaster {

// Defaults: the Livox Mid-360's IMU, a TDK InvenSense ICM-40609(-D) (Livox Mid-360 user manual).
struct ImuNoiseParameters {
  // Datasheet DS-000330 rev 1.2: gyroscope noise 4.5 mdps/sqrt(Hz), accelerometer 100 ug/sqrt(Hz).
  double gyro_noise_density = 4.5e-3 * M_PI / 180.0;  // rad/s/sqrt(Hz), = 7.85e-5
  double accel_noise_density = 100e-6 * 9.80665;      // m/s^2/sqrt(Hz), = 9.81e-4
  // The datasheet gives no bias random walk: these are assumed, values commonly used for MEMS
  // IMUs of this class in LIO configurations, not datasheet figures.
  double gyro_random_walk = 1e-5;   // rad/s^2/sqrt(Hz)
  double accel_random_walk = 1e-4;  // m/s^3/sqrt(Hz)
};

// The additive errors of one sample, per axis.
struct ImuErrors {
  Eigen::Vector3d gyro_white = Eigen::Vector3d::Zero();   // rad/s
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();    // rad/s
  Eigen::Vector3d accel_white = Eigen::Vector3d::Zero();  // m/s^2
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();   // m/s^2
  Eigen::Vector3d gyro() const { return gyro_white + gyro_bias; }
  Eigen::Vector3d accel() const { return accel_white + accel_bias; }
};

class ImuNoise {
 public:
  // Throws std::invalid_argument for a negative parameter or a rate that is not positive.
  ImuNoise(const ImuNoiseParameters& parameters, double rate_hz, std::uint64_t seed, std::uint64_t origin = 0);

  // The errors of sample `index`. The bias is the sum of the increments of samples origin..index-1
  // (zero before the origin): asking in increasing order costs O(1) per sample, asking for an
  // earlier index replays from the origin.
  ImuErrors at(std::uint64_t index);

  // Standard deviation of the white noise of one sample (noise_density * sqrt(rate)).
  double gyroWhiteStddev() const { return parameters_.gyro_noise_density / std::sqrt(dt_); }
  double accelWhiteStddev() const { return parameters_.accel_noise_density / std::sqrt(dt_); }

 private:
  struct Normals {  // the 12 standard normals of one sample, always drawn in this order
    Eigen::Vector3d gyro_white, accel_white, gyro_step, accel_step;
  };
  Normals draw(std::uint64_t index) const;

  ImuNoiseParameters parameters_;
  double dt_;
  std::uint64_t seed_;
  std::uint64_t origin_;
  std::uint64_t bias_index_;  // the biases below are those of sample bias_index_
  Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_ = Eigen::Vector3d::Zero();
};

}  // namespace uampc::raycaster
