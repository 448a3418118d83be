// tf_broadcaster: the rig's TF tree on /tf_static and /tf, so that a viewer (Foxglove, RViz) places
// every topic by its header's frame_id (docs/dev/architecture.md, "TF"). REP-105 names by default:
//
//   map -> odom -> base_link -> motor -> rotor -> lidar        (the LO's estimate)
//   map -> ground_truth                                          (the true base_link, simulation)
//
//   base_link -> motor   static, identity: the motor axis is base_link's z axis by definition
//                        (Eq. 1 has R_BM(theta) and no offset; adapters/rig_parameters.hpp)
//   rotor -> lidar       static, the rig's calibration (R_ML, r_ML), through adapters::rigCalibration
//   motor -> rotor       every /motor/state: R_BM(theta) of Eq. 1 (frames::motorRotation), theta the
//                        encoder's angle less the rig's encoder_offset_deg, stamped with the state's
//                        stamp less the rig's time_offset (the LiDAR's clock, frames::rotorReading);
//                        tf2 interpolates it at each point's own time
//   odom -> base_link    every /lo/odometry, with map -> odom (identity: the LO starts at the
//                        ground-truth pose, so its odometry frame is the map frame; lo/start_poses.hpp)
//   map -> ground_truth  every /ground_truth/pose
//
// What libs/frames calls M (the frame turned by theta) is "rotor" here; "motor" is the
// motor's fixed part. No core library: every transform is one frames or a message already holds;
// this adapter only names and stamps them.
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/tf2_msgs.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

namespace {

// The frame-name parameters with their REP-105 defaults, in one table.
struct FrameParameter {
  const char* name;
  const char* default_value;
  const char* doc;
};
constexpr FrameParameter kFrameParameters[] = {
    {"map_frame", "map", "world-fixed frame: ground truth, the world's mesh and points"},
    {"odom_frame", "odom", "the LO's odometry frame (parent of base_frame)"},
    {"base_frame", "base_link", "the robot's base, whose pose the LO estimates"},
    {"motor_frame", "motor", "the motor's fixed part (on base_frame, identity)"},
    {"rotor_frame", "rotor", "the motor's rotor, turned about motor_frame's z axis by the encoder angle"},
    {"lidar_frame", "lidar", "the LiDAR on the rotor (the raycaster's frame_id)"},
    {"ground_truth_frame", "ground_truth", "the true base pose, child of map_frame (simulation)"},
};

geometry_msgs::msg::TransformStamped transformMessage(const Eigen::Isometry3d& T, Time stamp, const std::string& parent,
                                                      const std::string& child) {
  const geometry_msgs::msg::Pose pose = adapters::toPoseMessage(T);
  geometry_msgs::msg::TransformStamped m;
  m.header().stamp(toMsg(stamp));
  m.header().frame_id(parent);
  m.child_frame_id(child);
  m.transform().translation().x(pose.position().x());
  m.transform().translation().y(pose.position().y());
  m.transform().translation().z(pose.position().z());
  m.transform().rotation(pose.orientation());
  return m;
}

}  // namespace

class TfBroadcaster : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary =
        "Publishes the rig's TF tree: /tf_static (base to motor, rotor to LiDAR) and /tf (encoder, LO, "
        "ground truth)";
    spec.input<sensor_msgs::msg::JointState>("motor_state", "/motor/state", QosPreset::kControl,
                                             "encoder states: motor_frame -> rotor_frame");
    spec.input<nav_msgs::msg::Odometry>("odometry", "/lo/odometry", QosPreset::kControl,
                                        "LO odometry: odom_frame -> base_frame (and map_frame -> odom_frame)");
    spec.input<geometry_msgs::msg::PoseStamped>("ground_truth", "/ground_truth/pose", QosPreset::kControl,
                                                "true base poses: map_frame -> ground_truth_frame");
    spec.output<tf2_msgs::msg::TFMessage>("tf", "/tf", QosPreset::kSensor,
                                          "one message per encoder state, odometry and ground-truth pose")
        .forViewers();
    spec.output<tf2_msgs::msg::TFMessage>("tf_static", "/tf_static", QosPreset::kLatched,
                                          "base_frame -> motor_frame and rotor_frame -> lidar_frame, once at start")
        .forViewers();
    adapters::declareRigParameters(spec);
    for (const FrameParameter& f : kFrameParameters) spec.param(f.name, f.default_value, f.doc);
    spec.param("map_to_odom", true,
               "publish map_frame -> odom_frame as identity with every odometry (right when the LO starts at the "
               "ground-truth pose, init_from_pose; false when a localiser publishes it)");
  }

  explicit TfBroadcaster(Context& ctx)
      : ctx_(ctx),
        map_(frameParam(ctx, "map_frame")),
        odom_(frameParam(ctx, "odom_frame")),
        base_(frameParam(ctx, "base_frame")),
        motor_(frameParam(ctx, "motor_frame")),
        rotor_(frameParam(ctx, "rotor_frame")),
        lidar_(frameParam(ctx, "lidar_frame")),
        ground_truth_(frameParam(ctx, "ground_truth_frame")),
        map_to_odom_(ctx.paramBool("map_to_odom")),
        calibration_(adapters::rigCalibration(ctx)),
        tf_pub_(ctx.publisher<tf2_msgs::msg::TFMessage>("tf")),
        tf_static_pub_(ctx.publisher<tf2_msgs::msg::TFMessage>("tf_static")) {
    checkDistinct();
    publishStatic(calibration_);
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state",
                                                [this](const sensor_msgs::msg::JointState& s) { onMotorState(s); });
    ctx.subscribe<nav_msgs::msg::Odometry>("odometry", [this](const nav_msgs::msg::Odometry& o) { onOdometry(o); });
    ctx.subscribe<geometry_msgs::msg::PoseStamped>(
        "ground_truth", [this](const geometry_msgs::msg::PoseStamped& p) { onGroundTruth(p); });
  }

 private:
  // tf2 refuses empty names and names with a leading '/'.
  static std::string frameParam(const Context& ctx, const char* name) {
    const std::string frame = ctx.paramString(name);
    if (frame.empty() || frame.front() == '/') {
      throw std::runtime_error(std::string("parameter '") + name +
                               "' must be a frame name without a leading '/', got '" + frame + "'");
    }
    return frame;
  }

  // Two roles under one name would make a loop or a frame with two parents in the tree.
  void checkDistinct() const {
    std::set<std::string> seen;
    for (const FrameParameter& f : kFrameParameters) {
      const std::string frame = ctx_.paramString(f.name);
      if (!seen.insert(frame).second) {
        throw std::runtime_error(std::string("parameter '") + f.name + "': frame '" + frame +
                                 "' is already another frame of the tree; every frame parameter needs its own name");
      }
    }
  }

  // Latched: written during construction, late joiners get it too (stamp: the start of the run).
  void publishStatic(const frames::MotorLidarCalibration& calibration) {
    Eigen::Isometry3d T_rotor_lidar = Eigen::Isometry3d::Identity();
    T_rotor_lidar.linear() = calibration.R_ML;
    T_rotor_lidar.translation() = calibration.r_ML;
    tf2_msgs::msg::TFMessage m;
    m.transforms().push_back(transformMessage(Eigen::Isometry3d::Identity(), ctx_.now(), base_, motor_));
    m.transforms().push_back(transformMessage(T_rotor_lidar, ctx_.now(), rotor_, lidar_));
    tf_static_pub_.publish(m);
  }

  void onMotorState(const sensor_msgs::msg::JointState& s) {
    if (s.position().empty() || !std::isfinite(s.position()[0])) {
      bad_state_log_.warn(ctx_.log(), "motor states on ", ctx_.topicOf("motor_state"),
                          " without a finite position are skipped (said once)");
      return;
    }
    // The rotor's angle (Eq. 1's theta) stamped on the LiDAR's clock, so that a viewer interpolating
    // motor -> rotor at a point's stamp gets the angle Eq. 1 uses. The stamp is shifted in whole
    // nanoseconds: a zero time_offset leaves it as the encoder stamped it.
    const frames::MotorReading rotor = frames::rotorReading({0.0, s.position()[0], 0.0}, calibration_);
    Eigen::Isometry3d T_motor_rotor = Eigen::Isometry3d::Identity();
    T_motor_rotor.linear() = frames::motorRotation(rotor.theta);
    const Time stamp = fromMsg(s.header().stamp()) - Time::fromSeconds(calibration_.time_offset);
    publish({transformMessage(T_motor_rotor, stamp, motor_, rotor_)});
  }

  void onOdometry(const nav_msgs::msg::Odometry& o) {
    if (!adapters::isFinitePose(o.pose().pose())) {
      bad_odometry_log_.warn(ctx_.log(), "odometry on ", ctx_.topicOf("odometry"),
                             " with a non-finite pose is skipped (said once)");
      return;
    }
    const Time stamp = fromMsg(o.header().stamp());
    std::vector<geometry_msgs::msg::TransformStamped> transforms;
    if (map_to_odom_) transforms.push_back(transformMessage(Eigen::Isometry3d::Identity(), stamp, map_, odom_));
    transforms.push_back(transformMessage(adapters::toIsometry(o.pose().pose()), stamp, odom_, base_));
    publish(std::move(transforms));
  }

  void onGroundTruth(const geometry_msgs::msg::PoseStamped& p) {
    if (!adapters::isFinitePose(p.pose())) {
      bad_pose_log_.warn(ctx_.log(), "ground-truth poses on ", ctx_.topicOf("ground_truth"),
                         " with a non-finite pose are skipped (said once)");
      return;
    }
    publish({transformMessage(adapters::toIsometry(p.pose()), fromMsg(p.header().stamp()), map_, ground_truth_)});
  }

  void publish(std::vector<geometry_msgs::msg::TransformStamped> transforms) {
    tf2_msgs::msg::TFMessage m;
    m.transforms(std::move(transforms));
    tf_pub_.publish(m);
  }

  Context& ctx_;
  const std::string map_, odom_, base_, motor_, rotor_, lidar_, ground_truth_;
  const bool map_to_odom_;
  const frames::MotorLidarCalibration calibration_;
  Publisher<tf2_msgs::msg::TFMessage> tf_pub_;
  Publisher<tf2_msgs::msg::TFMessage> tf_static_pub_;
  RateLimitedLog bad_state_log_ = RateLimitedLog::once();
  RateLimitedLog bad_odometry_log_ = RateLimitedLog::once();
  RateLimitedLog bad_pose_log_ = RateLimitedLog::once();
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::TfBroadcaster, "tf_broadcaster")
