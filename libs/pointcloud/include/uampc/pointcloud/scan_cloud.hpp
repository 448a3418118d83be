// sensor_msgs/PointCloud2 <-> plain vectors, in one place.
//
// uampc's scans carry the fields of docs/dev/architecture.md section 4: x, y, z, intensity, t
// (float32, seconds since the header stamp), ring (uint16); 22 bytes per point, little-endian,
// unorganised (height 1). The reader also accepts other drivers' layouts: the per-point time may be
// called t, time, timestamp or offset_time, in float32 or float64 seconds or integer nanoseconds
// (uint32, int32, uint64 as two uint32 is not a PointField type, so offset_time in uint32 ns as
// Livox's driver). A float64 field named timestamp is absolute time on the header stamp's clock, as
// the drivers that write it mean it: livox_ros_driver2 in nanoseconds, Hesai's and RoboSense's in
// seconds; seconds when the cloud's last point so read lies within kMaxTimeOffset of the header
// stamp, else nanoseconds when it does so (docs/user/rig.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "sensor_msgs/msg/PointCloud2.h"

namespace uampc::pointcloud {

struct ScanPoints {
  std::vector<Eigen::Vector3f> positions;  // m, in the cloud's frame
  std::vector<float> intensities;          // empty when the cloud has no intensity field
  std::vector<float> time_offsets;         // s since the header stamp; empty when no time field
  std::vector<std::uint16_t> rings;        // empty when the cloud has no ring field
};

// Builds a scan cloud with fields x, y, z, intensity, t, ring.
sensor_msgs::msg::PointCloud2 makeScanCloud(const ScanPoints& points, const std::string& frame_id);
// Builds a cloud in livox_ros_driver2's PointCloud2 layout (xfer_format 0): x, y, z, intensity
// (float32), tag, line (uint8), timestamp (float64, absolute ns), 26 bytes per point; line is the
// ring, tag 0. stamp_ns is the header stamp, the time the offsets count from.
sensor_msgs::msg::PointCloud2 makeLivoxCloud(const ScanPoints& points, const std::string& frame_id,
                                             std::int64_t stamp_ns);
// Builds a cloud with x, y, z only (maps, registered scans).
sensor_msgs::msg::PointCloud2 makeXyzCloud(const std::vector<Eigen::Vector3f>& points, const std::string& frame_id);

// How a cloud's time field is read; found once per layout, so a bad layout is reported once.
struct TimeField {
  std::string name;  // empty: the cloud has no usable time field
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  double scale = 1.0;  // to seconds (1e-9 for integer nanoseconds)
  // float64 "timestamp": absolute time on the header's clock, its unit found per cloud.
  bool absolute = false;
};

// Finds the time field, or throws std::runtime_error with a message naming the fields present
// and the accepted names and types.
TimeField findTimeField(const sensor_msgs::msg::PointCloud2& cloud);

// A point time farther than this from the header stamp, s, is read as NaN: no LiDAR frame lasts
// that long, and a point at 1e30 s (a driver's garbage) would hold its scan back for good (the
// LO waits for encoder states covering it, the evaluator for ground truth) or make the evaluator
// evaluate a pose every 0.25 ms over its span. Callers already skip points without a finite time.
constexpr double kMaxTimeOffset = 10.0;

// Adds `offset_s` to every point's time when the cloud's times are absolute (a float64 timestamp
// field), in the field's own unit; nothing for times relative to the header stamp. For a player
// that moves a recording to the present (its header stamps shift by the same offset).
void shiftAbsoluteTimes(sensor_msgs::msg::PointCloud2& cloud, double offset_s);
// Whether the cloud's point times are absolute (a float64 timestamp field).
bool hasAbsoluteTimes(const sensor_msgs::msg::PointCloud2& cloud);

// Reads x, y, z (float32 required), and intensity, ring and time where present. Throws
// std::runtime_error on an inconsistent cloud (data shorter than width*height*point_step, fields
// beyond point_step, big-endian data). Non-finite points are kept: callers decide and count.
ScanPoints readCloud(const sensor_msgs::msg::PointCloud2& cloud, const TimeField* time_field = nullptr);

}  // namespace uampc::pointcloud
