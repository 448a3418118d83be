#include "uampc/evaluator/motor_activity.hpp"

#include <cmath>
#include <stdexcept>

#include "uampc/evaluator/periodic_grid.hpp"

namespace uampc::evaluator {

MotorActivity::MotorActivity(double period) : period_(period) {
  if (!(period > 0.0) || !std::isfinite(period)) throw std::invalid_argument("MotorActivity: period must be positive");
}

void MotorActivity::add(double time, double speed, double command) {
  if (!std::isfinite(time) || !std::isfinite(speed) || !std::isfinite(command)) return;
  if (started_ && !(time > last_time_)) return;
  if (!started_) next_grid_time_ = time;
  started_ = true;
  last_time_ = time;
  ++samples_;
  speed_sum_ += speed;
  speed_square_sum_ += speed * speed;
  if (time + 1e-9 < next_grid_time_) return;
  // The first state at or after each grid point stands for it (the encoder is much faster).
  if (have_grid_point_) {
    const double command_change = command - grid_command_, speed_change = speed - grid_speed_;
    command_change_square_sum_ += command_change * command_change;
    speed_change_square_sum_ += speed_change * speed_change;
    ++changes_;
  }
  grid_speed_ = speed;
  grid_command_ = command;
  have_grid_point_ = true;
  next_grid_time_ = firstGridPointAfter(next_grid_time_, time + 1e-9, period_);
}

MotorActivityReport MotorActivity::report() const {
  MotorActivityReport r;
  if (samples_ == 0) return r;
  const double n = double(samples_);
  r.mean_speed = speed_sum_ / n;
  r.speed_std = std::sqrt(std::max(0.0, speed_square_sum_ / n - r.mean_speed * r.mean_speed));
  r.periods = changes_;
  if (changes_ > 0) {
    r.command_change_rms = std::sqrt(command_change_square_sum_ / double(changes_));
    r.speed_change_rms = std::sqrt(speed_change_square_sum_ / double(changes_));
  }
  return r;
}

}  // namespace uampc::evaluator
