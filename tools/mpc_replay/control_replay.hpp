// Replays UA-MPC's control steps from a run's uncertainty.csv (the evaluator writes one row per
// step: time, theta_start, delta_theta, command, then the U samples over one turn) with other
// controller options, to see what they do to the command (docs/results/controller-options.md)
// without rerunning the simulation. Open loop: the angles and U samples are the recorded run's, so
// what is measured is the controller's response to identical inputs, not where it would have
// steered the LiDAR.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "uampc/mpc/motor_mpc.hpp"

namespace uampc::tools {

struct ControlRecord {
  double time = 0.0;         // s
  double theta_start = 0.0;  // rad, angle of samples[0] (the encoder angle at the step)
  double sample_step = 0.0;  // rad
  double command = 0.0;      // rad/s, what the controller commanded in the run
  std::vector<double> samples;
};

// Throws std::runtime_error naming the file and line on unreadable or malformed rows.
std::vector<ControlRecord> readControlRecords(const std::string& path);

struct ReplayOptions {
  mpc::MotorMpc::Config mpc;  // alpha, beta, horizon, dt, bounds
  // Exponential filter of the U samples over control steps, per absolute motor angle:
  // F <- (1 - w) F + w U with w = filter_weight; 1 keeps every step's samples as they are.
  double filter_weight = 1.0;
  // Every sample_stride-th U sample only: a coarser delta_theta (the controller's sample_step_deg
  // times this), from the same recorded samples.
  int sample_stride = 1;
};

struct ReplayStats {
  std::size_t steps = 0;
  double recorded_change_rms = 0.0;  // rad/s, the run's command change per step
  double replayed_change_rms = 0.0;  // rad/s, with the options
  double replayed_mean = 0.0;        // rad/s
  double at_bounds = 0.0;            // share of steps at omega_min or omega_max (within 1e-3)
  double max_difference = 0.0;       // rad/s, largest |replayed - recorded| command
  std::vector<double> commands;      // replayed, one per record
};

// Throws std::invalid_argument on a filter weight outside (0, 1].
ReplayStats replayControl(const std::vector<ControlRecord>& records, const ReplayOptions& options);

}  // namespace uampc::tools
