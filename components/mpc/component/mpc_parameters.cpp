#include "mpc_parameters.hpp"

namespace uampc {

void bindMpcParameters(ParameterBinding& b, mpc::UaMpcController::Config& c) {
  using mpc::Mode;
  b.bindChoice("mode", c.mode,
               {{mpc::modeName(Mode::kUaMpc), Mode::kUaMpc},
                {mpc::modeName(Mode::kConstant), Mode::kConstant},
                {mpc::modeName(Mode::kZero), Mode::kZero}},
               "ua_mpc, constant or zero");
  b.bind("constant_speed", c.constant_speed, "mode constant: the speed, rad/s (the paper's baseline: 3.6)")
      .between(-100.0, 100.0);
  b.bind("alpha", c.mpc.alpha, "weight of the uncertainty term (used as is: cost = alpha * U'^2)").atLeast(0.0);
  b.bind("beta", c.mpc.beta, "weight of the preferred-speed term (cost = beta * (omega - omega_pre)^2)")
      .atLeast(0.0);
  b.bind("rate_weight", c.mpc.rate_weight,
         "beyond the paper: weight gamma of a rate term gamma * (omega_i - omega_(i-1))^2 over the horizon, the "
         "first against the last command; 0: off, the paper's cost")
      .between(0.0, 1e6);
  b.bind("omega_pre", c.mpc.omega_pre, "preferred speed and initial guess, rad/s").between(-100.0, 100.0);
  b.bind("omega_min", c.mpc.omega_min, "lower speed bound, rad/s").between(-100.0, 100.0);
  b.bind("omega_max", c.mpc.omega_max, "upper speed bound, rad/s").between(-100.0, 100.0);
  b.bind("horizon", c.mpc.horizon, "M: the MPC optimises M + 1 future speeds").between(1, 200);
  b.bind("horizon_dt", c.mpc.dt, "time between horizon steps, s").between(0.001, 10.0);
  b.bindDegrees("sample_step_deg", c.sample_step, "delta_theta between U samples, degrees").between(0.5, 90.0);
  b.bind("u_filter_weight", c.u_filter_weight,
         "U samples averaged over control steps per motor angle, F <- (1 - w) F + w U (1: each step's own, as "
         "in the paper; docs/results/controller-options.md)")
      .between(0.01, 1.0);
  b.bindDegrees("ray_step_deg", c.uncertainty.azimuth_step, "grid of the field-of-view rays for U, degrees")
      .between(0.5, 30.0);
  c.uncertainty.elevation_step = c.uncertainty.azimuth_step;  // one square grid
  b.bind("panorama_width", c.depth_map.width, "panorama columns over 2 pi").between(16, 4096);
  b.bind("panorama_height", c.depth_map.height, "panorama rows over pi").between(8, 2048);
  b.bind("range_weight_voxel", c.range_weight_voxel,
         "U weighs each ray by what an LO downsampling to voxels of this size keeps of it (the lo's "
         "scan_voxel_size, m; 0: every ray weighs 1, as in the paper; docs/results/u-check.md)")
      .between(0.0, 10.0);
}

}  // namespace uampc
