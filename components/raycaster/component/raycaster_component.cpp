// raycaster: the simulated motorized LiDAR (docs/dev/architecture.md section 2, Eq. 1).
// Rebuilds the world from map_provider's chunks, buffers ground-truth poses and encoder states,
// and renders frame k (covering [k/rate, (k+1)/rate)) as soon as both cover it: every point at
// its own time, with the motor turning during the frame. Publishes one PointCloud2 per frame in
// the LiDAR frame (x, y, z, intensity, t since the header stamp = frame start, ring).
// With `imu` on, it also publishes the LiDAR's built-in IMU (raycaster/imu_simulator.hpp), in the
// LiDAR frame and so turning with the motor: every sample k / imu_rate, in order, as soon as the
// buffered poses and encoder states cover its finite-difference stencil.
#include <algorithm>
#include <deque>
#include <memory>
#include <optional>

#include "scan_parameters.hpp"
#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/frames/gravity.hpp"
#include "uampc/raycaster/imu_simulator.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

class RaycasterComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Simulated motorized LiDAR: casts the scan pattern into the world at each point's own time";
    spec.input<msg::WorldMesh>("world", "/world/mesh", QosPreset::kLatched, "world surfaces from map_provider");
    spec.input<geometry_msgs::msg::PoseStamped>("ground_truth", "/ground_truth/pose", QosPreset::kControl,
                                                "ground-truth base pose");
    spec.input<sensor_msgs::msg::JointState>("motor_state", "/motor/state", QosPreset::kControl, "encoder states");
    spec.output<sensor_msgs::msg::PointCloud2>("scan", "/lidar/points", QosPreset::kSensor,
                                               "one frame, LiDAR frame, per-point time t")
        .soleWriter();
    spec.output<sensor_msgs::msg::Imu>("imu", "/lidar/imu", QosPreset::kSensor,
                                       "IMU in the LiDAR frame, turning with the motor (with imu: true)");
    adapters::declareLidarModelParameters(spec);
    adapters::declareRigParameters(spec);
    spec.param("frame_id", "lidar", "frame_id of the published scans and IMU samples");
    // livox: what a rig's driver publishes, so that a recording of a simulation can stand in for the
    // LiDAR of config/scenes/rig_mid360.yaml (docs/user/rig.md).
    spec.param("point_layout", "uampc",
               "layout of the published scans: 'uampc' (x, y, z, intensity, t, ring) or 'livox' "
               "(livox_ros_driver2's PointCloud2: x, y, z, intensity, tag, line, timestamp in absolute ns; the IMU's "
               "acceleration in g)")
        .oneOf({"uampc", "livox"});
    spec.param("imu", false, "publish the LiDAR's IMU (angular velocity and specific force in the LiDAR frame)");
    declareMountingErrorParameters(spec);
    raycaster::RayCasterConfig scan_defaults = sceneScanDefaults();
    raycaster::ImuSimulatorConfig imu_defaults;  // the Mid-360's IMU, an ICM-40609
    ParameterBinding binding(spec);
    bindScanParameters(binding, scan_defaults);
    bindImuParameters(binding, imu_defaults);
  }

  explicit RaycasterComponent(Context& ctx)
      : ctx_(ctx),
        config_(configFrom(ctx)),
        scan_pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("scan")),
        imu_pub_(ctx.publisher<sensor_msgs::msg::Imu>("imu")) {
    frame_id_ = ctx.paramString("frame_id");
    livox_layout_ = ctx.paramString("point_layout") == "livox";
    if (ctx.paramBool("imu")) imu_.emplace(imuConfigFrom(ctx, config_));
    ctx.subscribe<msg::WorldMesh>("world", [this](const msg::WorldMesh& m) { onWorld(m); });
    ctx.subscribe<geometry_msgs::msg::PoseStamped>("ground_truth", [this](const geometry_msgs::msg::PoseStamped& p) {
      onPose(p);
      render();
      publishImu();
    });
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state", [this](const sensor_msgs::msg::JointState& s) {
      onMotor(s);
      render();
      publishImu();
    });
  }

 private:
  // The parameters that set the core's configs: declared from their defaults, read into them.
  static void bindImuParameters(ParameterBinding& b, raycaster::ImuSimulatorConfig& c) {
    b.bind("imu_rate", c.rate_hz, "imu: sample rate, Hz").between(1.0, 1000.0);
    b.bind("gyro_noise_density", c.noise.gyro_noise_density,
           "imu: gyroscope white noise, rad/s/sqrt(Hz) (ICM-40609 datasheet: 4.5 mdps/sqrt(Hz))")
        .between(0.0, 1.0);
    b.bind("gyro_random_walk", c.noise.gyro_random_walk,
           "imu: gyroscope bias random walk, rad/s^2/sqrt(Hz) (assumed: the datasheet gives none)")
        .between(0.0, 1.0);
    b.bind("accel_noise_density", c.noise.accel_noise_density,
           "imu: accelerometer white noise, m/s^2/sqrt(Hz) (ICM-40609 datasheet: 100 ug/sqrt(Hz))")
        .between(0.0, 10.0);
    b.bind("accel_random_walk", c.noise.accel_random_walk,
           "imu: accelerometer bias random walk, m/s^3/sqrt(Hz) (assumed: the datasheet gives none)")
        .between(0.0, 10.0);
  }

  // A simulated rig that differs from the one the scene's rig: block describes, which every other
  // component believes: the raycaster casts with the believed rig composed with this error
  // (frames::withMountingError), so that a calibration has something to find
  // (docs/user/calibration.md).
  static void declareMountingErrorParameters(ComponentSpec& spec) {
    spec.param("mounting_error_rpy_deg", std::vector<double>{0.0, 0.0, 0.0},
               "simulated rig: the true R_ML is the rig's times R(roll, pitch, yaw) of these, in the LiDAR "
               "frame, degrees")
        .ofLength(3)
        .between(-180.0, 180.0);
    spec.param("mounting_error_offset", std::vector<double>{0.0, 0.0, 0.0},
               "simulated rig: the true r_ML is the rig's plus this, in the motor frame, m")
        .ofLength(3)
        .between(-10.0, 10.0);
    spec.param("mounting_error_encoder_deg", 0.0,
               "simulated rig: the true encoder zero is the rig's encoder_offset_deg plus this, degrees")
        .between(-180.0, 180.0);
    spec.param("mounting_error_time_offset", 0.0,
               "simulated rig: the true LiDAR-to-encoder clock offset is the rig's time_offset plus this, s")
        .between(-1.0, 1.0);
  }

  static frames::MountingError mountingErrorFrom(const Context& ctx) {
    frames::MountingError e;
    e.rotation_rpy = adapters::degreesToRadians(adapters::vector3Param(ctx, "mounting_error_rpy_deg"));
    e.offset = adapters::vector3Param(ctx, "mounting_error_offset");
    e.encoder_offset = ctx.paramDouble("mounting_error_encoder_deg") * M_PI / 180.0;
    e.time_offset = ctx.paramDouble("mounting_error_time_offset");
    return e;
  }

  static raycaster::RayCasterConfig configFrom(const Context& ctx) {
    raycaster::RayCasterConfig c;
    c.model = adapters::lidarModel(ctx);
    c.calibration = frames::withMountingError(adapters::rigCalibration(ctx), mountingErrorFrom(ctx));
    c.seed = ctx.seed();
    ParameterBinding binding(ctx);
    bindScanParameters(binding, c);
    return c;
  }

  static raycaster::ImuSimulatorConfig imuConfigFrom(const Context& ctx, const raycaster::RayCasterConfig& scans) {
    raycaster::ImuSimulatorConfig c;
    c.calibration = scans.calibration;
    c.seed = scans.seed;
    c.start_time = ctx.now().seconds();  // real time: now, not the epoch (docs/dev/time-and-lockstep.md)
    ParameterBinding binding(ctx);
    bindImuParameters(binding, c);
    return c;
  }

  void onWorld(const msg::WorldMesh& m) {
    if (caster_) return;  // the world is built once
    if (m.chunk_count() == 0 || m.chunk() >= m.chunk_count() || m.vertices().size() % 3 || m.triangles().size() % 3 ||
        m.points().size() % 3) {
      throw std::runtime_error("malformed world chunk on " + ctx_.topicOf("world") + " (chunk " +
                               std::to_string(m.chunk()) + " of " + std::to_string(m.chunk_count()) + ")");
    }
    const int base = static_cast<int>(mesh_.vertices.size());
    const std::size_t vertex_count = m.vertices().size() / 3;
    for (std::size_t i = 0; i < m.vertices().size(); i += 3) {
      mesh_.vertices.emplace_back(m.vertices()[i], m.vertices()[i + 1], m.vertices()[i + 2]);
    }
    for (std::size_t i = 0; i < m.triangles().size(); i += 3) {
      for (int k = 0; k < 3; ++k) {
        if (m.triangles()[i + k] >= vertex_count) {
          throw std::runtime_error("world chunk " + std::to_string(m.chunk()) + " on " + ctx_.topicOf("world") +
                                   " refers to a vertex it does not have");
        }
      }
      mesh_.triangles.emplace_back(base + static_cast<int>(m.triangles()[i]),
                                   base + static_cast<int>(m.triangles()[i + 1]),
                                   base + static_cast<int>(m.triangles()[i + 2]));
    }
    for (std::size_t i = 0; i < m.points().size(); i += 3) {
      points_.emplace_back(m.points()[i], m.points()[i + 1], m.points()[i + 2]);
    }
    chunks_seen_.resize(m.chunk_count(), false);
    chunks_seen_[m.chunk()] = true;
    if (std::find(chunks_seen_.begin(), chunks_seen_.end(), false) != chunks_seen_.end()) return;
    config_.point_radius = m.point_radius() > 0 ? m.point_radius() : config_.point_radius;
    caster_ = std::make_unique<raycaster::RayCaster>(mesh_, points_, config_);
    ctx_.log().info("world '", m.world(), "' received: ", mesh_.triangles.size(), " triangles, ", points_.size(),
                    " points");
  }

  void onPose(const geometry_msgs::msg::PoseStamped& p) {
    const double t = fromMsg(p.header().stamp()).seconds();
    if (!poses_.empty() && t <= poses_.back().time) return;  // repeated or stale: nothing new
    if (!adapters::isFinitePose(p.pose())) {
      throw std::runtime_error("invalid ground-truth pose on " + ctx_.topicOf("ground_truth") +
                               " at t=" + std::to_string(t));
    }
    const Eigen::Isometry3d T = adapters::toIsometry(p.pose());
    poses_.push_back({t, T.translation(), Eigen::Quaterniond(T.linear())});
  }

  void onMotor(const sensor_msgs::msg::JointState& s) {
    if (s.position().empty() || !std::isfinite(s.position()[0])) {
      throw std::runtime_error("motor state without a finite position on " + ctx_.topicOf("motor_state"));
    }
    // The rotor's true angle on the LiDAR's clock: the simulated rig's encoder zero and clock offset
    // (the believed rig's composed with mounting_error_*) taken out.
    const frames::MotorReading reading = frames::rotorReading(
        {fromMsg(s.header().stamp()).seconds(), s.position()[0], s.velocity().empty() ? 0.0 : s.velocity()[0]},
        config_.calibration);
    if (!motor_.add(reading) || !imu_) return;
    // The IMU takes the motor's rate from the encoder's velocity: its angle is quantised.
    if (s.velocity().empty() || !std::isfinite(s.velocity()[0])) {
      throw std::runtime_error("the IMU needs a finite velocity (the motor's rate) in the motor states on " +
                               ctx_.topicOf("motor_state"));
    }
    motor_rates_.push_back(reading);
    const double needed_from = next_imu_ ? imuStencilStart() : reading.time - 2.0;
    while (motor_rates_.size() > 2 && motor_rates_[1].time <= needed_from) motor_rates_.pop_front();
  }

  // theta_dot at t, linear between the encoder's velocity readings (held beyond them).
  double motorRateAt(double t) const {
    const auto after = std::lower_bound(motor_rates_.begin(), motor_rates_.end(), t,
                                        [](const frames::MotorReading& r, double time) { return r.time < time; });
    if (after == motor_rates_.begin()) return after->omega;
    if (after == motor_rates_.end()) return motor_rates_.back().omega;
    const frames::MotorReading& before = *(after - 1);
    return before.omega + (t - before.time) / (after->time - before.time) * (after->omega - before.omega);
  }

  // Renders every frame the buffers cover, oldest first.
  void render() {
    if (!caster_) return;
    const double period = caster_->frameDuration();
    if (!chooseFirstFrame(period)) return;
    for (;;) {
      const double start = static_cast<double>(next_frame_) * period;
      const double end = start + period;
      if (poses_.empty() || poses_.front().time > start || poses_.back().time < end || !motor_.covers(start, end)) {
        return;
      }
      const world::Trajectory window(std::vector<world::TimedPose>(poses_.begin(), poses_.end()));
      const raycaster::Scan scan = caster_->castFrame(next_frame_, start, window, motor_);
      publish(scan);
      ++next_frame_;
      // Poses before the next frame's start (and the next IMU sample's stencil) are not needed any
      // more (keep one for interpolation).
      const double needed_from = next_imu_ ? std::min(end, imuStencilStart()) : end;
      while (poses_.size() > 2 && poses_[1].time <= needed_from) poses_.pop_front();
    }
  }

  // Frames are cast at k * period. The first is the first the buffers hold from its start on:
  // frame 0 in lockstep, whose poses and encoder states start at 0; in real time, whose clock reads
  // the Unix epoch's seconds, the first after the run's start (docs/dev/time-and-lockstep.md).
  // False while there is nothing to choose from.
  bool chooseFirstFrame(double period) {
    if (first_frame_chosen_) return true;
    if (poses_.empty() || motor_.empty()) return false;
    const double from = std::max(poses_.front().time, motor_.oldest().time);
    next_frame_ = from > 0.0 ? static_cast<std::uint64_t>(std::ceil(from / period)) : 0;
    first_frame_chosen_ = true;
    return true;
  }

  // The earliest time the next IMU sample needs poses and encoder states from.
  double imuStencilStart() const { return imu_->sampleTime(*next_imu_) - raycaster::kImuStencilHalfWidth; }

  // Publishes every IMU sample the buffers cover, oldest first, each once.
  void publishImu() {
    if (!imu_ || poses_.empty() || motor_rates_.empty()) return;
    const double w = raycaster::kImuStencilHalfWidth;
    const double covered_until = std::min(poses_.back().time, motor_.newest().time);
    if (!next_imu_ || poses_.front().time > imuStencilStart() || !motor_.covers(imuStencilStart(), covered_until)) {
      // The first sample, or the history no longer reaches back to the next one (the encoder's
      // is kept 2 s; poses stopped for longer than that): start at the first one covered.
      const double from = std::max(poses_.front().time, motor_.oldest().time) + w;
      if (next_imu_) {
        ctx_.log().warn("IMU: no poses or encoder states around t=", imu_->sampleTime(*next_imu_),
                        " s any more; resuming at t=", from, " s");
      }
      next_imu_ = std::max(next_imu_.value_or(0), imu_->firstIndexAtOrAfter(from));
    }
    if (imu_->sampleTime(*next_imu_) + w > covered_until) return;
    // The poses from the one before the first stencil's start on.
    auto first = std::upper_bound(poses_.begin(), poses_.end(), imuStencilStart(),
                                  [](double time, const world::TimedPose& p) { return time < p.time; });
    if (first != poses_.begin()) --first;
    const world::Trajectory window(std::vector<world::TimedPose>(first, poses_.end()));
    const raycaster::ImuMotion motion{[&window](double t) { return window.poseAt(t); },
                                      [this](double t) { return motor_.thetaAt(t).value(); },
                                      [this](double t) { return motorRateAt(t); }};
    for (; imu_->sampleTime(*next_imu_) + w <= covered_until; ++*next_imu_) {
      publishImuSample(imu_->sample(*next_imu_, motion));
    }
  }

  void publishImuSample(const raycaster::ImuSample& sample) {
    sensor_msgs::msg::Imu m;
    m.header().stamp(toMsg(Time::fromSeconds(sample.time)));
    m.header().frame_id(frame_id_);
    // No orientation: sensor_msgs/Imu asks for orientation_covariance[0] = -1 then.
    m.orientation().w(1.0);
    m.orientation_covariance()[0] = -1.0;
    m.angular_velocity().x(sample.angular_velocity.x());
    m.angular_velocity().y(sample.angular_velocity.y());
    m.angular_velocity().z(sample.angular_velocity.z());
    // The driver's layout gives acceleration in g, as livox_ros_driver2 does (docs/user/rig.md).
    const Eigen::Vector3d a = livox_layout_ ? Eigen::Vector3d(sample.linear_acceleration / frames::kStandardGravity)
                                            : Eigen::Vector3d(sample.linear_acceleration);
    m.linear_acceleration().x(a.x());
    m.linear_acceleration().y(a.y());
    m.linear_acceleration().z(a.z());
    // The white noise of one sample (the bias drifts, unknown to a user, as on the real sensor).
    for (const int diagonal : {0, 4, 8}) {
      m.angular_velocity_covariance()[diagonal] = imu_->gyroNoiseVariance();
      m.linear_acceleration_covariance()[diagonal] =
          imu_->accelNoiseVariance() / (livox_layout_ ? frames::kStandardGravity * frames::kStandardGravity : 1.0);
    }
    imu_pub_.publish(m);
  }

  void publish(const raycaster::Scan& scan) {
    pointcloud::ScanPoints points;
    points.positions.reserve(scan.points.size());
    for (const auto& p : scan.points) {
      points.positions.push_back(p.position);
      points.intensities.push_back(p.intensity);
      points.time_offsets.push_back(p.time_offset);
      points.rings.push_back(p.ring);
    }
    const Time stamp = Time::fromSeconds(scan.stamp);
    auto cloud = livox_layout_ ? pointcloud::makeLivoxCloud(points, frame_id_, stamp.ns)
                               : pointcloud::makeScanCloud(points, frame_id_);
    cloud.header().stamp(toMsg(stamp));
    scan_pub_.publish(cloud);
  }

  Context& ctx_;
  raycaster::RayCasterConfig config_;
  Publisher<sensor_msgs::msg::PointCloud2> scan_pub_;
  Publisher<sensor_msgs::msg::Imu> imu_pub_;
  std::string frame_id_;
  bool livox_layout_ = false;
  world::TriangleMesh mesh_;
  std::vector<Eigen::Vector3f> points_;
  std::vector<bool> chunks_seen_;
  std::unique_ptr<raycaster::RayCaster> caster_;
  std::deque<world::TimedPose> poses_;
  frames::MotorAngleTrack motor_{2.0};
  std::uint64_t next_frame_ = 0;
  bool first_frame_chosen_ = false;
  std::optional<raycaster::ImuSimulator> imu_;    // with imu: true
  std::deque<frames::MotorReading> motor_rates_;  // encoder velocities, for the IMU
  std::optional<std::uint64_t> next_imu_;         // the next IMU sample to publish
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::RaycasterComponent, "raycaster")
