// raycaster: the simulated motorized LiDAR (DESIGN.md section 2, Eq. 1).
// Rebuilds the world from map_provider's chunks, buffers ground-truth poses and encoder states,
// and renders frame k (covering [k/rate, (k+1)/rate)) as soon as both cover it: every point at
// its own time, with the motor turning during the frame. Publishes one PointCloud2 per frame in
// the LiDAR frame (x, y, z, intensity, t since the header stamp = frame start, ring).
#include <deque>
#include <memory>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/runtime/component.hpp"

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
                                               "one frame, LiDAR frame, per-point time t");
    spec.param("model", "livox_mid360", "LiDAR model: livox_mid360, velodyne_vlp16, livox_avia or spinning")
        .oneOf({"livox_mid360", "velodyne_vlp16", "livox_avia", "spinning"});
    spec.param("elevations_deg", std::vector<double>{-15, -13, -11, -9, -7, -5, -3, -1, 1, 3, 5, 7, 9, 11, 13, 15},
               "model: spinning: the beam elevations, degrees");
    spec.param("points_per_second", 288000.0, "model: spinning: points per second").between(1.0, 1e8);
    spec.param("frame_rate", 10.0, "model: spinning: frames per second, Hz").between(0.1, 100.0);
    spec.param("min_range", 0.5, "model: spinning: minimum range, m").between(0.0, 1000.0);
    spec.param("max_range", 100.0, "model: spinning: maximum range, m").between(0.1, 10000.0);
    adapters::declareRigParameters(spec);
    spec.param("range_noise", 0.0, "standard deviation of Gaussian range noise, m").between(0.0, 1.0);
    spec.param("dropout", 0.0, "probability that a return is lost").between(0.0, 1.0);
    spec.param("frame_id", "lidar", "frame_id of the published scans");
  }

  explicit RaycasterComponent(Context& ctx)
      : ctx_(ctx), config_(configFrom(ctx)), scan_pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("scan")) {
    frame_id_ = ctx.paramString("frame_id");
    ctx.subscribe<msg::WorldMesh>("world", [this](const msg::WorldMesh& m) { onWorld(m); });
    ctx.subscribe<geometry_msgs::msg::PoseStamped>("ground_truth", [this](const geometry_msgs::msg::PoseStamped& p) {
      onPose(p);
      render();
    });
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state", [this](const sensor_msgs::msg::JointState& s) {
      onMotor(s);
      render();
    });
  }

 private:
  static raycaster::RayCasterConfig configFrom(const Context& ctx) {
    raycaster::RayCasterConfig c;
    const std::string model = ctx.paramString("model");
    c.model = model == "spinning"
                  ? raycaster::spinningLidar(ctx.paramDoubleList("elevations_deg"), ctx.paramDouble("points_per_second"),
                                             ctx.paramDouble("frame_rate"), ctx.paramDouble("min_range"),
                                             ctx.paramDouble("max_range"))
                  : raycaster::lidarModelByName(model);
    c.calibration = adapters::rigCalibration(ctx);
    c.range_noise_stddev = ctx.paramDouble("range_noise");
    c.dropout_probability = ctx.paramDouble("dropout");
    c.seed = ctx.seed();
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
      mesh_.triangles.emplace_back(base + static_cast<int>(m.triangles()[i]), base + static_cast<int>(m.triangles()[i + 1]),
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
      throw std::runtime_error("invalid ground-truth pose on " + ctx_.topicOf("ground_truth") + " at t=" +
                               std::to_string(t));
    }
    const Eigen::Isometry3d T = adapters::toIsometry(p.pose());
    poses_.push_back({t, T.translation(), Eigen::Quaterniond(T.linear())});
  }

  void onMotor(const sensor_msgs::msg::JointState& s) {
    if (s.position().empty() || !std::isfinite(s.position()[0])) {
      throw std::runtime_error("motor state without a finite position on " + ctx_.topicOf("motor_state"));
    }
    motor_.add({fromMsg(s.header().stamp()).seconds(), s.position()[0], s.velocity().empty() ? 0.0 : s.velocity()[0]});
  }

  // Renders every frame the buffers cover, oldest first.
  void render() {
    if (!caster_) return;
    const double period = caster_->frameDuration();
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
      // Poses before the next frame's start are not needed any more (keep one for interpolation).
      while (poses_.size() > 2 && poses_[1].time <= end) poses_.pop_front();
    }
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
    auto cloud = pointcloud::makeScanCloud(points, frame_id_);
    cloud.header().stamp(toMsg(Time::fromSeconds(scan.stamp)));
    scan_pub_.publish(cloud);
  }

  Context& ctx_;
  raycaster::RayCasterConfig config_;
  Publisher<sensor_msgs::msg::PointCloud2> scan_pub_;
  std::string frame_id_;
  world::TriangleMesh mesh_;
  std::vector<Eigen::Vector3f> points_;
  std::vector<bool> chunks_seen_;
  std::unique_ptr<raycaster::RayCaster> caster_;
  std::deque<world::TimedPose> poses_;
  frames::MotorAngleTrack motor_{2.0};
  std::uint64_t next_frame_ = 0;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::RaycasterComponent, "raycaster")
