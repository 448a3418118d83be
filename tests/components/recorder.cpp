// Test component: records what arrives on its ports, as it arrives, to CSV files in the run's
// output directory (<name>_motor_states.csv, _motor_commands.csv, _ground_truth.csv, _scans.csv,
// _imu.csv, and one file per TF edge: _tf_<parent>_to_<child>.csv, _tf_static_<parent>_to_<child>.csv),
// at full precision, so that tests can check the data and compare runs byte for byte.
#include <cstdio>
#include <map>
#include <memory>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/tf2_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class Recorder : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: records motor states, commands, ground truth, scans, IMU samples and TF to CSV";
    spec.input<sensor_msgs::msg::JointState>("state", "/motor/state", QosPreset::kControl, "motor states");
    spec.input<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "motor commands");
    spec.input<geometry_msgs::msg::PoseStamped>("ground_truth", "/ground_truth/pose", QosPreset::kControl,
                                                "ground-truth poses");
    spec.input<sensor_msgs::msg::PointCloud2>("scan", "/lidar/points", QosPreset::kSensor, "LiDAR scans");
    spec.input<sensor_msgs::msg::Imu>("imu", "/lidar/imu", QosPreset::kSensor, "IMU samples");
    spec.input<tf2_msgs::msg::TFMessage>("tf", "/tf", QosPreset::kSensor, "transforms");
    spec.input<tf2_msgs::msg::TFMessage>("tf_static", "/tf_static", QosPreset::kLatched, "static transforms");
    spec.param("max_scans", 5, "scans recorded (the first ones after skip_scans)").atLeast(0);
    spec.param("skip_scans", 0, "scans skipped before recording starts").atLeast(0);
  }

  explicit Recorder(Context& ctx)
      : ctx_(ctx), max_scans_(ctx.paramInt("max_scans")), skip_scans_(ctx.paramInt("skip_scans")) {
    if (ctx.outputDirectory().empty()) throw std::runtime_error("recorder needs an output directory (--out)");
    states_ = open("motor_states.csv", "stamp,position,velocity\n");
    commands_ = open("motor_commands.csv", "received,stamp,velocity\n");
    poses_ = open("ground_truth.csv", "stamp,x,y,z,qx,qy,qz,qw\n");
    scans_ = open("scans.csv", "stamp,x,y,z,intensity,t,ring\n");
    imu_ = open("imu.csv", "stamp,wx,wy,wz,ax,ay,az\n");
    ctx.subscribe<sensor_msgs::msg::JointState>("state", [this](const sensor_msgs::msg::JointState& m) {
      std::fprintf(states_.get(), "%.9f,%.17g,%.17g\n", fromMsg(m.header().stamp()).seconds(), m.position().at(0),
                   m.velocity().at(0));
    });
    ctx.subscribe<msg::MotorCommand>("command", [this](const msg::MotorCommand& m) {
      std::fprintf(commands_.get(), "%.9f,%.9f,%.17g\n", ctx_.now().seconds(), fromMsg(m.header().stamp()).seconds(),
                   m.velocity());
    });
    ctx.subscribe<geometry_msgs::msg::PoseStamped>("ground_truth", [this](const geometry_msgs::msg::PoseStamped& m) {
      const auto& p = m.pose().position();
      const auto& q = m.pose().orientation();
      std::fprintf(poses_.get(), "%.9f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                   fromMsg(m.header().stamp()).seconds(), p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
    });
    ctx.subscribe<sensor_msgs::msg::PointCloud2>("scan", [this](const sensor_msgs::msg::PointCloud2& m) {
      const std::int64_t index = scans_seen_++;
      if (index < skip_scans_ || index >= skip_scans_ + max_scans_) return;
      const auto time_field = pointcloud::findTimeField(m);
      const auto points = pointcloud::readCloud(m, &time_field);
      const double stamp = fromMsg(m.header().stamp()).seconds();
      for (std::size_t i = 0; i < points.positions.size(); ++i) {
        const auto& p = points.positions[i];
        std::fprintf(scans_.get(), "%.9f,%.9g,%.9g,%.9g,%.9g,%.9g,%u\n", stamp, p.x(), p.y(), p.z(),
                     points.intensities[i], points.time_offsets[i], points.rings[i]);
      }
    });
    ctx.subscribe<sensor_msgs::msg::Imu>("imu", [this](const sensor_msgs::msg::Imu& m) {
      const auto& w = m.angular_velocity();
      const auto& a = m.linear_acceleration();
      std::fprintf(imu_.get(), "%.9f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", fromMsg(m.header().stamp()).seconds(),
                   w.x(), w.y(), w.z(), a.x(), a.y(), a.z());
    });
    ctx.subscribe<tf2_msgs::msg::TFMessage>("tf", [this](const tf2_msgs::msg::TFMessage& m) { recordTf("tf", m); });
    ctx.subscribe<tf2_msgs::msg::TFMessage>("tf_static",
                                            [this](const tf2_msgs::msg::TFMessage& m) { recordTf("tf_static", m); });
  }

 private:
  using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
  File open(const char* name, const char* header) {
    const std::string path = ctx_.outputDirectory() + "/" + ctx_.name() + "_" + name;
    File f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fputs(header, f.get());
    return f;
  }

  // One file per edge (parent -> child), opened at the edge's first transform.
  void recordTf(const std::string& topic, const tf2_msgs::msg::TFMessage& m) {
    for (const auto& t : m.transforms()) {
      const std::string file = topic + "_" + t.header().frame_id() + "_to_" + t.child_frame_id() + ".csv";
      auto it = tf_files_.find(file);
      if (it == tf_files_.end()) it = tf_files_.emplace(file, open(file.c_str(), "stamp,x,y,z,qx,qy,qz,qw\n")).first;
      const auto& p = t.transform().translation();
      const auto& q = t.transform().rotation();
      std::fprintf(it->second.get(), "%.9f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                   fromMsg(t.header().stamp()).seconds(), p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
    }
  }

  Context& ctx_;
  std::int64_t max_scans_;
  std::int64_t skip_scans_;
  std::int64_t scans_seen_ = 0;
  File states_{nullptr, &std::fclose};
  File commands_{nullptr, &std::fclose};
  File poses_{nullptr, &std::fclose};
  File scans_{nullptr, &std::fclose};
  File imu_{nullptr, &std::fclose};
  std::map<std::string, File> tf_files_;  // by file name
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::Recorder, "csv_recorder")
