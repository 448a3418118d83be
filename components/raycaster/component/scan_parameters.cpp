#include "scan_parameters.hpp"

#include "uampc/lidar/lidar_model.hpp"

namespace uampc {

raycaster::RayCasterConfig sceneScanDefaults() {
  raycaster::RayCasterConfig c;
  // The core casts exactly (range_noise_stddev 0), as its range tests rely on; a scene gets the
  // default model's datasheet precision (1 sigma).
  c.range_noise_stddev = lidar::livoxMid360().range_precision;
  return c;
}

void bindScanParameters(ParameterBinding& b, raycaster::RayCasterConfig& c) {
  // The Mid-360's angular precision (0.15 degrees, 1 sigma) is modelled but off by default: with
  // it the LiDAR-only LO loses the MCD worlds' open stretches within 10-45 s and the rich campus
  // at 3 m/s (docs/results/sensor-noise.md); a scene may turn it on.
  b.bindDegrees("angular_noise_deg", c.angular_noise_stddev,
                "standard deviation of the reported direction of a return, per axis, degrees (the Mid-360 "
                "datasheet: 0.15; off by default, see docs/results/sensor-noise.md)")
      .between(0.0, 10.0);
  b.bind("dropout", c.dropout_probability, "probability that a return is lost").between(0.0, 1.0);
  b.bindChoice("frame_timing", c.frame_timing,
               {{"continuous", raycaster::FrameTiming::kContinuous}, {"snapshot", raycaster::FrameTiming::kSnapshot}},
               "when a frame's rays are cast: 'continuous', each at its own time (a real LiDAR: the base and "
               "the motor move during the frame), or 'snapshot', all from the one pose at the frame's stamp, "
               "time offsets 0 (the paper's reference simulator; docs/results/table-1-reference-regime.md)");
  b.bind("range_noise", c.range_noise_stddev,
         "standard deviation of Gaussian range noise, m (default: the Mid-360 datasheet, 2 cm at 10 m)")
      .between(0.0, 1.0);
}

}  // namespace uampc
