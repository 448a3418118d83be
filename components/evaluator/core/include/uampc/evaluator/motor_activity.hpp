// What the motor did, beyond its mean speed: how much the command and the speed change from one
// control period to the next (UA-MPC's command chatters: docs/results/controller-options.md), taken
// on a fixed grid of `period` seconds so that the encoder rate does not enter the figures.
#pragma once

#include <cstddef>

namespace uampc::evaluator {

struct MotorActivityReport {
  double mean_speed = 0.0;          // rad/s
  double speed_std = 0.0;           // rad/s, standard deviation of the speed over the run
  double command_change_rms = 0.0;  // rad/s, RMS of the command's change over one period
  double speed_change_rms = 0.0;    // rad/s, RMS of the speed's change over one period
  std::size_t periods = 0;          // changes counted
};

class MotorActivity {
 public:
  // period: the grid of the changes, s (the controller's period: 0.1 s at 10 Hz). Throws
  // std::invalid_argument when not positive.
  explicit MotorActivity(double period = 0.1);

  // One encoder state with the command in force then; times increasing. Non-finite values and
  // times not after the last one are ignored.
  void add(double time, double speed, double command);

  MotorActivityReport report() const;

 private:
  double period_;
  double last_time_ = 0.0;
  bool started_ = false;
  double next_grid_time_ = 0.0;
  double grid_speed_ = 0.0, grid_command_ = 0.0;  // the values at the last grid point
  bool have_grid_point_ = false;
  std::size_t samples_ = 0;
  double speed_sum_ = 0.0, speed_square_sum_ = 0.0;
  std::size_t changes_ = 0;
  double command_change_square_sum_ = 0.0, speed_change_square_sum_ = 0.0;
};

}  // namespace uampc::evaluator
