// Test component: a misbehaving LiDAR driver. Publishes scans on /lidar/points that the LO must
// survive: without a per-point time field, with NaN points, with non-finite point times, or empty.
#include <limits>

#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class BadScanPublisher : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: publishes malformed scans";
    spec.output<sensor_msgs::msg::PointCloud2>("scan", "/lidar/points", QosPreset::kSensor, "malformed scans");
    spec.requiredParam("mode", ParameterType::kString, "no_time, nan_points, bad_times or empty")
        .oneOf({"no_time", "nan_points", "bad_times", "empty"});
  }

  explicit BadScanPublisher(Context& ctx)
      : ctx_(ctx), mode_(ctx.paramString("mode")), pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("scan")) {
    ctx.timer(0.1, [this] { publish(); });
  }

 private:
  void publish() {
    pointcloud::ScanPoints points;
    if (mode_ != "empty") {
      for (int i = 0; i < 2000; ++i) {
        const float a = 0.01f * static_cast<float>(i);
        points.positions.emplace_back(5.0f * std::cos(a), 5.0f * std::sin(a), 0.1f * static_cast<float>(i % 20));
        points.time_offsets.push_back(0.1f * static_cast<float>(i) / 2000.0f);
        points.intensities.push_back(1.0f);
        points.rings.push_back(0);
      }
      if (mode_ == "nan_points") {
        for (int i = 0; i < 2000; i += 7) points.positions[i].x() = std::numeric_limits<float>::quiet_NaN();
      }
      if (mode_ == "bad_times") {
        for (int i = 0; i < 2000; i += 7) points.time_offsets[i] = std::numeric_limits<float>::quiet_NaN();
        for (int i = 3; i < 2000; i += 11) points.time_offsets[i] = std::numeric_limits<float>::infinity();
      }
    }
    sensor_msgs::msg::PointCloud2 cloud = mode_ == "no_time" ? pointcloud::makeXyzCloud(points.positions, "lidar")
                                                             : pointcloud::makeScanCloud(points, "lidar");
    cloud.header().stamp(toMsg(ctx_.now()));
    pub_.publish(cloud);
  }

  Context& ctx_;
  std::string mode_;
  Publisher<sensor_msgs::msg::PointCloud2> pub_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::BadScanPublisher, "bad_scan_publisher")
