#include "lo_parameters.hpp"

namespace uampc {

void bindLoParameters(ParameterBinding& b, lo::OdometryConfig& c) {
  b.bind("scan_voxel_size", c.scan_voxel_size, "voxel downsampling of the scan, m").between(0.01, 10.0);
  b.bind("max_registration_points", c.max_registration_points,
         "a downsampled scan with more points registers this many, spread evenly over space (0: all; see "
         "docs/results/lo-degenerate-geometry.md, \"A registration budget\")")
      .between(0, 10000000);
  b.bind("registration_weakest_points", c.registration_weakest_points,
         "with max_registration_points, enough points register that the weakest pose direction keeps this many "
         "effective points (poor geometry registers every point; 0: the budget alone)")
      .between(0.0, 1e6);
  b.bind("map_voxel_size", c.map_voxel_size, "voxel size of the local map, m").between(0.01, 10.0);
  b.bind("map_mean_points", c.map_mean_points,
         "a map voxel's point is the mean of its first this many observations (1: the first point stays; see "
         "docs/results/lo-degenerate-geometry.md, \"The map's points\")")
      .between(1, 255);
  b.bind("map_radius", c.map_radius, "local-map points farther than this from the base are dropped, m")
      .between(1.0, 10000.0);
  b.bind("measurement_variance", c.measurement_variance, "point-to-plane measurement variance, m^2")
      .between(1e-9, 100.0);
  b.bind("linear_process_noise", c.linear_process_noise,
         "linear velocity random walk density of the constant-velocity model, (m/s)^2/s")
      .between(0.0, 100.0);
  b.bind("angular_process_noise", c.angular_process_noise,
         "angular velocity random walk density of the constant-velocity model, (rad/s)^2/s")
      .between(0.0, 100.0);
  b.bind("max_iterations", c.max_iterations, "iterated EKF: at most this many re-linearisations").between(1, 100);
  b.bind("degeneracy_aware", c.degeneracy_aware,
         "leave the state directions a scan does not constrain to the motion prior (suits LiDAR-inertial rigs in "
         "corridors and tunnels; see docs/decisions/lo-degeneracy-aware-off.md)");
  b.bind("frame_velocity_std_linear", c.frame_velocity_std_linear,
         "how far a frame's deskew velocity may differ from the filter's, m/s; 0 with frame_velocity_std_angular "
         "0: the paper's LO, the filter's velocity deskews every frame (see "
         "docs/results/lo-degenerate-geometry.md, \"Each frame's own velocity\")")
      .between(0.0, 100.0);
  b.bind("frame_velocity_std_angular", c.frame_velocity_std_angular,
         "how far a frame's deskew angular velocity may differ from the filter's, rad/s (see "
         "frame_velocity_std_linear)")
      .between(0.0, 100.0);
  b.bind("degeneracy_threshold", c.degeneracy_threshold,
         "a direction with fewer effective points than this is degenerate (reported in /lo/metrics)")
      .between(0.0, 1e6);
  b.bind("max_linear_acceleration", c.max_linear_acceleration, "an update needing more is rejected and counted, m/s^2")
      .between(0.0, 1e6);
  b.bind("max_angular_acceleration", c.max_angular_acceleration,
         "an update needing more is rejected and counted, rad/s^2")
      .between(0.0, 1e6);
  b.bind("initial_map_time", c.initial_map_time,
         "the first map over this long, s: scans are placed by the initial state and not registered (for a rig "
         "that stands still at the start, map_provider's start_hold; 0: the first scan alone)")
      .between(0.0, 60.0);
  b.bind("lost_after", c.lost_after, "lost: no registration accepted for longer than this, s").between(0.0, 3600.0);
  b.bind("velocity_reset_window", c.velocity_reset_window,
         "after a rejected update or at a loss of track, the velocity is reset to the accepted poses' mean motion "
         "over this long, s; 0: off (see docs/decisions/lo-velocity-reset.md)")
      .between(0.0, 10.0);
  b.bind("max_speed", c.max_speed, "an update leaving the speed above this is rejected, lost or not, m/s")
      .between(0.1, 1000.0);
  b.bind("max_angular_speed", c.max_angular_speed,
         "an update leaving the angular speed above this is rejected, lost or not, rad/s")
      .between(0.1, 1000.0);
  b.bind("use_imu", c.use_imu,
         "LiDAR-inertial mode: the IMU on the imu port replaces the constant-velocity prediction (beyond the "
         "paper, whose LO is LiDAR-only)");
  b.bind("gyro_noise_density", c.imu_noise.gyro_noise_density, "use_imu: gyroscope white noise, rad/s/sqrt(Hz)")
      .between(0.0, 1.0);
  b.bind("accel_noise_density", c.imu_noise.accel_noise_density,
         "use_imu: accelerometer white noise, m/s^2/sqrt(Hz)")
      .between(0.0, 10.0);
  b.bind("min_range", c.min_range, "points nearer than this (LiDAR frame) are dropped, m").between(0.0, 100.0);
  b.bind("max_range", c.max_range, "points farther than this are dropped, m").between(0.1, 10000.0);
  b.bind("plane_max_point_distance", c.plane_max_point_distance,
         "a plane fit is rejected if one of its neighbours lies farther from it than this, m")
      .between(0.001, 10.0);
  b.bind("max_neighbour_distance", c.max_neighbour_distance,
         "a plane is fitted only if the farthest of its 5 map neighbours is nearer than this, m (I2EKF-LO: "
         "sqrt(5) = 2.236)")
      .between(0.01, 100.0);
  b.bindChoice("deskew", c.deskew,
               {{"time", lo::DeskewMode::kTime}, {"index", lo::DeskewMode::kIndex}, {"none", lo::DeskewMode::kNone}},
               "which time places each point in the deskew: 'time', its own; 'index', its place in the frame spread "
               "from the previous scan's end to this one's (I2EKF-LO's with the reference simulator); 'none', the "
               "scan's end");
  b.bindChoice("imu_acceleration_unit", c.imu_acceleration_unit,
               {{"auto", lo::AccelerationUnit::kAuto},
                {"m/s^2", lo::AccelerationUnit::kMetresPerSecondSquared},
                {"g", lo::AccelerationUnit::kStandardGravity}},
               "use_imu: the unit of the IMU's acceleration: 'm/s^2' as sensor_msgs/Imu says, 'g' as "
               "livox_ros_driver2 publishes it, 'auto' told apart by the first 50 readings' mean (about 1 or 9.8)");
  b.bindChoice("association_gate", c.association_gate,
               {{"residual", lo::AssociationGate::kResidual},
                {"range_scaled", lo::AssociationGate::kRangeScaled},
                {"model_deviation", lo::AssociationGate::kModelDeviation}},
               "which correspondences register: 'residual', all until converged, then within 3 robust standard "
               "deviations; 'range_scaled', FAST-LIO2's and I2EKF-LO's 1 - 0.9 |residual| / sqrt(range) > 0.9 at "
               "every association; 'model_deviation', as 'residual' with the gate 3 times the motion model's RMS "
               "deviation (KISS-ICP's adaptive threshold)");
  b.bind("match_seen_side_only", c.match_seen_side_only,
         "match a map plane only from the side its points were seen from (docs/decisions/lo-seen-side-planes.md; "
         "I2EKF-LO has no such check)");
  b.bind("plane_min_spread_ratio", c.plane_min_spread_ratio,
         "a plane fit is rejected if its neighbours' narrower in-plane spread is below this share of the wider "
         "(0: any)")
      .between(0.0, 1.0);
  b.bind("degeneracy_length", c.degeneracy_scales.length,
         "the length that makes rotations and translations comparable in the degeneracy analysis, m")
      .between(0.001, 1000.0);
  b.bind("degeneracy_period", c.degeneracy_scales.period,
         "the time that makes velocities comparable with poses in the degeneracy analysis, s")
      .between(0.001, 1000.0);
}

}  // namespace uampc
