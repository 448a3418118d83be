// lo: LiDAR odometry for a motorized LiDAR (docs/dev/architecture.md sections 1 and 2). Takes scans
// in the LiDAR frame with per-point times and the encoder states, runs uampc_lo_core, and publishes
// the base odometry with covariance, the registered scan and the local map (world frame), and its
// figures (degeneracy, correspondences, processing time).
#include <chrono>
#include <cctype>
#include <deque>
#include <limits>
#include <map>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/lo/scan_readiness.hpp"
#include "uampc/lo/start_poses.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/component.hpp"
#include "lo_parameters.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

class LoComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Iterated-EKF point-to-plane LiDAR odometry for a LiDAR spun by a motor";
    spec.input<sensor_msgs::msg::PointCloud2>("scan", "/lidar/points", QosPreset::kSensor,
                                              "scans, LiDAR frame, per-point time (t, time, timestamp or offset_time)");
    spec.input<sensor_msgs::msg::JointState>("motor_state", "/motor/state", QosPreset::kControl, "encoder states");
    spec.input<sensor_msgs::msg::Imu>("imu", "/lidar/imu", QosPreset::kSensor,
                                      "IMU in the LiDAR frame (used with use_imu: LiDAR-inertial mode)");
    spec.input<geometry_msgs::msg::PoseStamped>("initial_pose", "/ground_truth/pose", QosPreset::kControl,
                                                "start pose (first sample used when init_from_pose is true)");
    spec.output<nav_msgs::msg::Odometry>("odometry", "/lo/odometry", QosPreset::kControl,
                                         "base pose and twist with covariance at the scan end")
        .soleWriter();
    spec.output<sensor_msgs::msg::PointCloud2>("registered", "/lo/registered", QosPreset::kSensor,
                                               "the scan, deskewed, in the world frame");
    spec.output<sensor_msgs::msg::PointCloud2>("local_map", "/lo/local_map", QosPreset::kSensor,
                                               "local map points observed in the last local_map_window s");
    spec.output<msg::Metrics>("metrics", "/lo/metrics", QosPreset::kSensor,
                              "status, lost, degenerate directions and eigenvalues, correspondences, processing time");
    adapters::declareRigParameters(spec);
    spec.param("init_from_pose", true, "start at the pose (and velocity) on initial_pose at the first scan; false: identity, at rest");
    lo::OdometryConfig defaults;
    ParameterBinding binding(spec);
    bindLoParameters(binding, defaults);
    spec.param("local_map_window", 5.0, "the published local map holds points seen in the last N s")
        .between(0.1, 3600.0);
    spec.param("max_motor_wait", 0.5, "a scan waits at most this long for encoder states covering it, s")
        .between(0.0, 10.0);
  }

  explicit LoComponent(Context& ctx)
      : ctx_(ctx),
        init_from_pose_(ctx.paramBool("init_from_pose")),
        window_(ctx.paramDouble("local_map_window")),
        max_motor_wait_(ctx.paramDouble("max_motor_wait")),
        odometry_pub_(ctx.publisher<nav_msgs::msg::Odometry>("odometry")),
        registered_pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("registered")),
        local_map_pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("local_map")),
        metrics_pub_(ctx.publisher<msg::Metrics>("metrics")) {
    config_ = configFrom(ctx);
    acceleration_unit_ = lo::AccelerationUnitDetector(config_.imu_acceleration_unit);
    ctx.subscribe<sensor_msgs::msg::PointCloud2>("scan", [this](const sensor_msgs::msg::PointCloud2& m) {
      onScan(m);
      processReady();
    });
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state", [this](const sensor_msgs::msg::JointState& s) {
      if (s.position().empty() || !std::isfinite(s.position()[0])) {
        throw std::runtime_error("motor state without a finite position on " + ctx_.topicOf("motor_state"));
      }
      // The rotor's angle on the LiDAR's clock: the rig's encoder zero and clock offset taken out.
      motor_.add(frames::rotorReading(
          {fromMsg(s.header().stamp()).seconds(), s.position()[0], s.velocity().empty() ? 0.0 : s.velocity()[0]},
          config_.calibration));
      processReady();
    });
    // Subscribed whatever use_imu says: every declared port must be opened.
    ctx.subscribe<sensor_msgs::msg::Imu>("imu", [this](const sensor_msgs::msg::Imu& m) {
      if (!config_.use_imu) return;
      onImu(m);
      processReady();
    });
    ctx.subscribe<geometry_msgs::msg::PoseStamped>("initial_pose", [this](const geometry_msgs::msg::PoseStamped& p) {
      if (!odometry_) start_poses_.add(fromMsg(p.header().stamp()).seconds(), adapters::toIsometry(p.pose()));
    });
  }

 private:

  static lo::OdometryConfig configFrom(const Context& ctx) {
    lo::OdometryConfig c;
    c.calibration = adapters::rigCalibration(ctx);
    ParameterBinding binding(ctx);
    bindLoParameters(binding, c);
    return c;
  }

  void onScan(const sensor_msgs::msg::PointCloud2& m) {
    // The time field is looked up once per layout: a cloud we cannot read is reported once.
    const std::string layout = layoutOf(m);
    if (layout != layout_) {
      layout_ = layout;
      try {
        time_field_ = pointcloud::findTimeField(m);
        layout_error_.clear();
      } catch (const std::exception& e) {
        layout_error_ = e.what();
        ctx_.log().error("cannot use scans on ", ctx_.topicOf("scan"), ": ", layout_error_,
                         "; such scans are skipped (said once per layout)");
      }
    }
    if (!layout_error_.empty()) return;
    pointcloud::ScanPoints points = pointcloud::readCloud(m, &time_field_);
    lo::Scan scan;
    scan.stamp = fromMsg(m.header().stamp()).seconds();
    scan.points_L = std::move(points.positions);
    scan.time_offsets = std::move(points.time_offsets);
    pending_.push_back(std::move(scan));
  }

  // Readings go to the odometry; before it exists (it starts at the first scan, from the start
  // pose) they wait in pending_imu_. A reading with a non-finite value or out of time order is
  // refused and reported once.
  void onImu(const sensor_msgs::msg::Imu& m) {
    const auto& w = m.angular_velocity();
    const auto& a = m.linear_acceleration();
    const lo::ImuReading reading{fromMsg(m.header().stamp()).seconds(), {w.x(), w.y(), w.z()}, {a.x(), a.y(), a.z()}};
    if (acceleration_unit_.scale()) return takeImu(scaled(reading));
    // Until the unit is known (acceleration_unit.hpp) the readings wait, as published.
    if (!reading.specific_force_L.allFinite()) return takeImu(reading);  // refused there, and said
    unit_pending_.push_back(reading);
    if (!acceleration_unit_.observe(reading.specific_force_L)) return;
    ctx_.log().info(acceleration_unit_.decision());
    for (const lo::ImuReading& r : unit_pending_) takeImu(scaled(r));
    unit_pending_.clear();
  }

  lo::ImuReading scaled(lo::ImuReading reading) const {
    reading.specific_force_L *= *acceleration_unit_.scale();
    return reading;
  }

  void takeImu(const lo::ImuReading& reading) {
    bool taken = false;
    if (odometry_) {
      taken = odometry_->addImu(reading);
    } else if (lo::usableImuReading(reading, newestImuTime())) {
      pending_imu_.push_back(reading);
      if (pending_imu_.size() > 400) pending_imu_.pop_front();  // 2 s at 200 Hz: the first scan needs less
      taken = true;
    }
    if (!taken) {
      bad_imu_log_.warn(ctx_.log(), "IMU readings on ", ctx_.topicOf("imu"),
                        " with non-finite values or out of time order are skipped (said once)");
    }
  }

  double newestImuTime() const {
    if (odometry_) return odometry_->newestImuTime();
    return pending_imu_.empty() ? -std::numeric_limits<double>::infinity() : pending_imu_.back().time;
  }

  static std::string layoutOf(const sensor_msgs::msg::PointCloud2& m) {
    std::string s = std::to_string(m.point_step());
    for (const auto& f : m.fields()) s += "|" + f.name() + ":" + std::to_string(f.offset()) + ":" + std::to_string(f.datatype());
    return s;
  }

  // Registers the scans whose points the encoder states cover (or that waited long enough).
  void processReady() {
    while (!pending_.empty()) {
      const lo::Scan& scan = pending_.front();
      const double imu_until = config_.use_imu ? newestImuTime() : std::numeric_limits<double>::infinity();
      if (!lo::readyToRegister(scan, motor_, imu_until, max_motor_wait_)) return;
      if (init_from_pose_ && !odometry_ && !initialise(lo::scanEndTime(scan))) return;
      if (!odometry_) {
        odometry_ = std::make_unique<lo::MotorizedLidarOdometry>(config_);
        for (const lo::ImuReading& r : pending_imu_) odometry_->addImu(r);
        pending_imu_.clear();
      }
      process(scan);
      pending_.pop_front();
    }
  }

  // The start pose and velocity from initial_pose at the first scan's end (lo/start_poses.hpp).
  bool initialise(double scan_end) {
    const std::optional<lo::StartState> start = start_poses_.at(scan_end);
    if (!start) {
      if (ctx_.now().seconds() > 2.0) {
        no_pose_log_.warn(ctx_.log(), "waiting for a pose on ", ctx_.topicOf("initial_pose"),
                          " to start from (init_from_pose: true); scans are queued");
      }
      return false;
    }
    config_.initial_pose = start->T_WB;
    config_.initial_velocity_W = start->velocity_W;
    config_.initial_angular_velocity_B = start->angular_velocity_B;
    start_poses_.clear();
    return true;
  }

  void process(const lo::Scan& scan) {
    const auto start = std::chrono::steady_clock::now();
    const lo::OdometryResult r = odometry_->registerScan(scan, motor_);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.status == lo::OdometryStatus::kRejected) {
      ctx_.log().warn("scan at ", scan.stamp, " s rejected: ", r.warning);
      return;
    }
    if (!r.warning.empty()) warnRepeated(r.warning);
    if (r.dropped_non_finite) {
      non_finite_log_.warn(ctx_.log(), "scans on ", ctx_.topicOf("scan"),
                           " contain non-finite points; they are dropped and counted");
    }
    const Time stamp = Time::fromSeconds(r.time);
    publishOdometry(r, stamp);
    auto registered = pointcloud::makeXyzCloud(r.registered_points_W, "odom");  // the LO's world frame
    registered.header().stamp(toMsg(stamp));
    registered_pub_.publish(registered);
    odometry_->localMap().pointsSince(r.time - window_, local_points_);
    auto local_map = pointcloud::makeXyzCloud(local_points_, "odom");
    local_map.header().stamp(toMsg(stamp));
    local_map_pub_.publish(local_map);
    publishMetrics(r, stamp, seconds);
  }

  // A warning that repeats every scan would drown the log: each kind (its text without numbers)
  // is said the 1st, 10th, 100th ... time.
  void warnRepeated(const std::string& warning) {
    std::string kind;
    for (char c : warning) {
      if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.' && c != '-') kind += c;
    }
    RateLimitedLog& log = repeated_logs_.try_emplace(kind, RateLimitedLog::atPowersOf(10)).first->second;
    if (!log.due()) return;
    const long n = log.occurrences();
    ctx_.log().warn(warning, n > 1 ? " (" + std::to_string(n) + " times so far)" : std::string());
  }

  void publishOdometry(const lo::OdometryResult& r, Time stamp) {
    adapters::BaseOdometry o;
    o.stamp = stamp;
    o.T_WB = r.T_WB;
    // ROS expresses the twist in the child frame: rotate the world-frame velocity into the base.
    o.linear_velocity_B = r.T_WB.linear().transpose() * r.linear_velocity_W;
    o.angular_velocity_B = r.angular_velocity_B;
    // The filter orders its state (rotation, position, linear velocity (world frame), angular velocity).
    o.pose_covariance = adapters::positionFirst(r.covariance.topLeftCorner<6, 6>());
    o.twist_covariance = r.covariance.bottomRightCorner<6, 6>();
    odometry_pub_.publish(adapters::toOdometryMessage(o));
  }

  void publishMetrics(const lo::OdometryResult& r, Time stamp, double seconds) {
    msg::Metrics m;
    m.header().stamp(toMsg(stamp));
    m.source(ctx_.name());
    auto add = [&](const char* name, double value, const char* unit) {
      msg::MetricValue v;
      v.name(name);
      v.value(value);
      v.unit(unit);
      m.values().push_back(v);
    };
    // status: 0 initialised, 1 tracking, 2 degenerate, 3 predicted-only, 5 lost (lo::OdometryStatus).
    add("status", static_cast<double>(r.status), "");
    add("lost", r.lost ? 1.0 : 0.0, "");
    add("rejected_updates", static_cast<double>(r.rejected_updates), "");
    add("velocity_resets", static_cast<double>(r.velocity_resets), "");
    // With use_imu: m/s^2 per unit of the IMU's acceleration as read (1, or 9.80665 for g), once known.
    if (acceleration_unit_.scale()) add("imu_acceleration_scale", *acceleration_unit_.scale(), "");
    add("min_information_eigenvalue", r.min_information_eigenvalue, "");
    // Every eigenvalue of the scaled pose information (effective points, ascending), and each
    // degenerate direction as [rotation * degeneracy length, translation] (unit vector, m).
    static const char* const kEigenvalueNames[6] = {"information_eigenvalue_1", "information_eigenvalue_2",
                                                   "information_eigenvalue_3", "information_eigenvalue_4",
                                                   "information_eigenvalue_5", "information_eigenvalue_6"};
    for (int i = 0; i < 6; ++i) add(kEigenvalueNames[i], r.degeneracy.eigenvalues(i), "");
    add("degenerate_directions", r.degeneracy.degenerate_directions, "");
    add("degenerate_state_directions", r.degenerate_state_directions, "");
    static const char* const kAxes[6] = {"rx", "ry", "rz", "x", "y", "z"};
    for (int d = 0; d < r.degeneracy.degenerate_directions; ++d) {
      for (int i = 0; i < 6; ++i) {
        const std::string name = "degenerate_direction_" + std::to_string(d + 1) + "_" + kAxes[i];
        add(name.c_str(), r.degeneracy.eigenvectors(i, d), "");
      }
    }
    add("correspondences", static_cast<double>(r.correspondences), "");
    add("iterations", r.iterations, "");
    add("points_used", static_cast<double>(r.points_used), "");
    add("processing_time", seconds, "s");
    metrics_pub_.publish(m);
  }

  Context& ctx_;
  lo::OdometryConfig config_;
  bool init_from_pose_;
  double window_;
  double max_motor_wait_;
  Publisher<nav_msgs::msg::Odometry> odometry_pub_;
  Publisher<sensor_msgs::msg::PointCloud2> registered_pub_;
  Publisher<sensor_msgs::msg::PointCloud2> local_map_pub_;
  std::vector<Eigen::Vector3f> local_points_;  // the published local map, reused frame to frame
  Publisher<msg::Metrics> metrics_pub_;
  std::unique_ptr<lo::MotorizedLidarOdometry> odometry_;
  frames::MotorAngleTrack motor_{2.0};
  std::deque<lo::Scan> pending_;
  std::deque<lo::ImuReading> pending_imu_;  // readings before the odometry starts
  lo::AccelerationUnitDetector acceleration_unit_{lo::AccelerationUnit::kAuto};  // set from config_
  std::vector<lo::ImuReading> unit_pending_;  // readings before their unit is known (at most 50)
  RateLimitedLog bad_imu_log_ = RateLimitedLog::once();
  lo::StartPoses start_poses_;  // initial_pose samples until the odometry starts
  std::string layout_;
  std::string layout_error_;
  pointcloud::TimeField time_field_;
  std::map<std::string, RateLimitedLog> repeated_logs_;  // by kind of warning
  RateLimitedLog no_pose_log_ = RateLimitedLog::once();
  RateLimitedLog non_finite_log_ = RateLimitedLog::once();
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::LoComponent, "lo")
