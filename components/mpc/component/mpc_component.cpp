// mpc: the motor controller (docs/dev/architecture.md section 1; the paper's Section II). Mode
// ua_mpc runs UA-MPC on the LO's local map and pose; modes constant and zero are the paper's
// baselines. Every control period it publishes the motor command, the uncertainty profile (U
// samples, the planned horizon, predicted U), the panoramic depth map as a 32FC1 image, and its
// timings.
#include <algorithm>
#include <cstring>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/mpc/ua_mpc_controller.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/runtime/component.hpp"
#include "mpc_parameters.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

class MpcComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "UA-MPC motor controller, with the constant- and zero-speed baselines as modes";
    spec.input<nav_msgs::msg::Odometry>("odometry", "/lo/odometry", QosPreset::kControl, "base pose from the LO");
    spec.input<sensor_msgs::msg::PointCloud2>("local_map", "/lo/local_map", QosPreset::kSensor,
                                              "the LO's local map, world frame");
    spec.input<sensor_msgs::msg::JointState>("motor_state", "/motor/state", QosPreset::kControl, "encoder states");
    spec.output<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "speed command, rad/s")
        .soleWriter();
    spec.output<msg::UncertaintyProfile>("profile", "/mpc/uncertainty", QosPreset::kSensor,
                                         "U samples over one turn, planned horizon, predicted U");
    spec.output<sensor_msgs::msg::Image>("panorama", "/mpc/panorama", QosPreset::kSensor,
                                         "panoramic depth map (32FC1, m; 0 = empty)");
    spec.output<msg::Metrics>("timing", "/mpc/timing", QosPreset::kSensor, "computation time per stage, s");
    mpc::UaMpcController::Config defaults;
    ParameterBinding binding(spec);
    bindMpcParameters(binding, defaults);
    spec.param("rate", 10.0, "control rate, Hz").between(0.1, 1000.0);
    adapters::declareLidarModelParameters(spec);  // U's field of view and point density
    adapters::declareRigParameters(spec);
    spec.param("stale_after", 1.0, "a local map older than this is stale: command omega_pre, s").between(0.01, 3600.0);
    spec.param("publish_panorama", true, "publish the panoramic depth map image");
  }

  explicit MpcComponent(Context& ctx)
      : ctx_(ctx),
        calibration_(adapters::rigCalibration(ctx)),
        controller_(configFrom(ctx)),
        stale_after_(Time::fromSeconds(ctx.paramDouble("stale_after"))),
        omega_pre_(ctx.paramDouble("omega_pre")),
        publish_panorama_(ctx.paramBool("publish_panorama")),
        command_pub_(ctx.publisher<msg::MotorCommand>("command")),
        profile_pub_(ctx.publisher<msg::UncertaintyProfile>("profile")),
        panorama_pub_(ctx.publisher<sensor_msgs::msg::Image>("panorama")),
        timing_pub_(ctx.publisher<msg::Metrics>("timing")) {
    ctx.subscribe<nav_msgs::msg::Odometry>("odometry", [this](const nav_msgs::msg::Odometry& m) { onOdometry(m); });
    ctx.subscribe<sensor_msgs::msg::PointCloud2>("local_map",
                                                 [this](const sensor_msgs::msg::PointCloud2& m) { onLocalMap(m); });
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state", [this](const sensor_msgs::msg::JointState& m) {
      // U(theta) is planned over the rotor's angle: the encoder's zero taken out (the control step
      // uses the newest angle, so the clock offset does not matter here).
      if (!m.position().empty() && std::isfinite(m.position()[0]))
        theta_ = frames::rotorReading({0.0, m.position()[0], 0.0}, calibration_).theta;
    });
    ctx.timer(1.0 / ctx.paramDouble("rate"), [this] { control(); });
  }

 private:

  static mpc::UaMpcController::Config configFrom(const Context& ctx) {
    mpc::UaMpcController::Config c;
    ParameterBinding binding(ctx);
    bindMpcParameters(binding, c);
    if (c.mpc.omega_min > c.mpc.omega_max) throw std::runtime_error("omega_min is above omega_max");
    c.uncertainty.calibration = adapters::rigCalibration(ctx);
    // The field of view of U comes from the same LiDAR model description as the simulator's.
    const lidar::LidarModel model = adapters::lidarModel(ctx);
    c.uncertainty.field_of_view = lidar::fieldOfView(model);
    c.depth_map.max_range = model.max_range;
    c.range_weight_voxel = ctx.paramDouble("range_weight_voxel");
    c.lidar_points_per_frame = lidar::nominalPointsPerFrame(model);
    return c;
  }

  void onOdometry(const nav_msgs::msg::Odometry& m) {
    if (!adapters::isFinitePose(m.pose().pose())) {
      ctx_.log().warn("ignoring an odometry message with a non-finite pose on ", ctx_.topicOf("odometry"));
      return;
    }
    T_WB_ = adapters::toIsometry(m.pose().pose());
    have_pose_ = true;
  }

  void onLocalMap(const sensor_msgs::msg::PointCloud2& m) {
    // The baselines never look at the map: do not convert 100k points ten times a second for them.
    if (controller_.config().mode != mpc::Mode::kUaMpc) return;
    // Kept as float, as it came: the depth map widens each point to double itself.
    local_map_ = pointcloud::readCloud(m).positions;
    const auto finite_end = std::remove_if(local_map_.begin(), local_map_.end(),
                                           [](const Eigen::Vector3f& p) { return !p.allFinite(); });
    const auto bad = static_cast<std::size_t>(local_map_.end() - finite_end);
    local_map_.erase(finite_end, local_map_.end());
    if (bad) ctx_.log().warn("dropped ", bad, " non-finite points of the local map on ", ctx_.topicOf("local_map"));
    local_map_time_ = ctx_.now();
  }

  void control() {
    const Time now = ctx_.now();
    const bool uses_map = controller_.config().mode == mpc::Mode::kUaMpc;
    const bool stale = !have_pose_ || local_map_.empty() || now - local_map_time_ > stale_after_;
    mpc::UaMpcController::Decision decision;
    if (uses_map && stale) {
      // Nothing to plan on: the preferred speed keeps the LiDAR sweeping (and the LO fed).
      if (now.seconds() > 1.0) {
        stale_log_.warn(ctx_.log(), "no recent local map or pose (", ctx_.topicOf("local_map"), ", ",
                        ctx_.topicOf("odometry"), "); commanding omega_pre ", omega_pre_, " rad/s");
      }
      decision.omega = omega_pre_;
      decision.local_map_empty = true;
    } else {
      if (stale_log_.said() && uses_map) {
        ctx_.log().info("local map available again; planning");
        stale_log_.reset();
      }
      decision = controller_.stepFloat(T_WB_, local_map_, theta_);
    }
    msg::MotorCommand command;
    command.header().stamp(toMsg(now));
    command.header().frame_id("motor");  // the rotor's speed about the motor frame's z axis
    command.velocity(decision.omega);
    command_pub_.publish(command);
    publishProfile(decision, now);
    if (uses_map && !stale && publish_panorama_) publishPanorama(now);
    publishTimings(decision, now);
  }

  void publishProfile(const mpc::UaMpcController::Decision& d, Time now) {
    msg::UncertaintyProfile profile;
    profile.header().stamp(toMsg(now));
    profile.header().frame_id("motor");  // U over encoder angles, measured in the motor frame
    profile.theta_start(d.sample_start);
    profile.delta_theta(d.sample_step);
    profile.samples(d.samples);
    profile.dt(controller_.config().mpc.dt);
    profile.horizon_omega(d.plan.speeds);
    profile.horizon_theta(d.plan.angles);
    profile.horizon_uncertainty(d.plan.predicted_uncertainty);
    profile.command(d.omega);
    profile_pub_.publish(profile);
  }

  void publishPanorama(Time now) {
    const auto& map = controller_.depthMap();
    const std::vector<float>& depth = map.depthImage();
    sensor_msgs::msg::Image image;
    image.header().stamp(toMsg(now));
    image.header().frame_id("base_link");  // azimuth and elevation about the base axes (Eq. 5)
    image.width(static_cast<std::uint32_t>(controller_.config().depth_map.width));
    image.height(static_cast<std::uint32_t>(controller_.config().depth_map.height));
    image.encoding("32FC1");
    image.is_bigendian(0);
    image.step(image.width() * 4);
    image.data().resize(depth.size() * 4);
    std::memcpy(image.data().data(), depth.data(), depth.size() * 4);
    panorama_pub_.publish(image);
  }

  void publishTimings(const mpc::UaMpcController::Decision& d, Time now) {
    msg::Metrics metrics;
    metrics.header().stamp(toMsg(now));
    metrics.source(ctx_.name());
    auto add = [&](const char* name, double ms) {
      msg::MetricValue v;
      v.name(name);
      v.value(ms * 1e-3);
      v.unit("s");
      metrics.values().push_back(v);
    };
    add("depth_map", d.timings.depth_map_ms);
    add("uncertainty", d.timings.uncertainty_ms);
    add("solve", d.timings.solve_ms);
    add("total", d.timings.total_ms);
    timing_pub_.publish(metrics);
  }

  Context& ctx_;
  frames::MotorLidarCalibration calibration_;
  mpc::UaMpcController controller_;
  Time stale_after_;
  double omega_pre_;
  bool publish_panorama_;
  Publisher<msg::MotorCommand> command_pub_;
  Publisher<msg::UncertaintyProfile> profile_pub_;
  Publisher<sensor_msgs::msg::Image> panorama_pub_;
  Publisher<msg::Metrics> timing_pub_;
  Eigen::Isometry3d T_WB_ = Eigen::Isometry3d::Identity();
  bool have_pose_ = false;
  std::vector<Eigen::Vector3f> local_map_;
  Time local_map_time_;
  double theta_ = 0.0;
  RateLimitedLog stale_log_ = RateLimitedLog::once();  // said again after the map came back
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::MpcComponent, "mpc")
