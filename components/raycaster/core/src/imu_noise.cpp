#include "uampc/raycaster/imu_noise.hpp"

#include <stdexcept>

#include "uampc/world/seeded_random.hpp"

namespace uampc::raycaster {

namespace {
// Keeps the IMU's streams apart from the scans', which are seeded from (seed, frame index).
constexpr std::uint64_t kImuStream = 0x494D55;  // "IMU"
}  // namespace

ImuNoise::ImuNoise(const ImuNoiseParameters& parameters, double rate_hz, std::uint64_t seed, std::uint64_t origin)
    : parameters_(parameters),
      dt_(1.0 / rate_hz),
      seed_(world::mixSeed(seed, kImuStream)),
      origin_(origin),
      bias_index_(origin) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw std::invalid_argument("ImuNoise: rate must be > 0");
  if (!(parameters.gyro_noise_density >= 0.0) || !(parameters.accel_noise_density >= 0.0) ||
      !(parameters.gyro_random_walk >= 0.0) || !(parameters.accel_random_walk >= 0.0)) {
    throw std::invalid_argument("ImuNoise: noise densities and random walks must be >= 0");
  }
}

ImuNoise::Normals ImuNoise::draw(std::uint64_t index) const {
  world::SeededRandom random(world::mixSeed(seed_, index));
  auto vector = [&random] {
    const double x = random.normal(), y = random.normal();
    return Eigen::Vector3d(x, y, random.normal());
  };
  Normals n;
  n.gyro_white = vector();
  n.accel_white = vector();
  n.gyro_step = vector();
  n.accel_step = vector();
  return n;
}

ImuErrors ImuNoise::at(std::uint64_t index) {
  if (index < bias_index_) {
    bias_index_ = origin_;
    gyro_bias_.setZero();
    accel_bias_.setZero();
  }
  const double sqrt_dt = std::sqrt(dt_);
  for (; bias_index_ < index; ++bias_index_) {
    const Normals n = draw(bias_index_);
    gyro_bias_ += parameters_.gyro_random_walk * sqrt_dt * n.gyro_step;
    accel_bias_ += parameters_.accel_random_walk * sqrt_dt * n.accel_step;
  }
  const Normals n = draw(index);
  ImuErrors e;
  e.gyro_white = gyroWhiteStddev() * n.gyro_white;
  e.accel_white = accelWhiteStddev() * n.accel_white;
  e.gyro_bias = gyro_bias_;
  e.accel_bias = accel_bias_;
  return e;
}

}  // namespace uampc::raycaster
