#include "uampc/pointcloud/scan_cloud.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace uampc::pointcloud {

namespace {

constexpr std::uint8_t kUint8 = 2, kInt32 = 5, kUint32 = 6, kFloat32 = 7, kFloat64 = 8, kUint16 = 4;

sensor_msgs::msg::PointField field(const char* name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::msg::PointField f;
  f.name(name);
  f.offset(offset);
  f.datatype(type);
  f.count(1);
  return f;
}

void setLayout(sensor_msgs::msg::PointCloud2& cloud, std::size_t count, std::uint32_t point_step,
               const std::string& frame_id) {
  cloud.header().frame_id(frame_id);
  cloud.height(1);
  cloud.width(static_cast<std::uint32_t>(count));
  cloud.is_bigendian(false);
  cloud.point_step(point_step);
  cloud.row_step(static_cast<std::uint32_t>(point_step * count));
  cloud.is_dense(true);
  cloud.data().resize(point_step * count);
}

std::size_t sizeOf(std::uint8_t datatype) {
  switch (datatype) {
    case 1:
    case 2:
      return 1;
    case 3:
    case 4:
      return 2;
    case 5:
    case 6:
    case 7:
      return 4;
    case 8:
      return 8;
  }
  return 0;
}

const sensor_msgs::msg::PointField* find(const sensor_msgs::msg::PointCloud2& cloud, const std::string& name) {
  for (const auto& f : cloud.fields()) {
    if (f.name() == name) return &f;
  }
  return nullptr;
}

template <typename T>
T readAs(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

double headerSeconds(const sensor_msgs::msg::PointCloud2& cloud) {
  return cloud.header().stamp().sec() + 1e-9 * cloud.header().stamp().nanosec();
}

// The unit of absolute point times, to seconds: seconds if the last point read so lies within a
// frame of the header stamp, else nanoseconds if it does read so (else seconds: the times are
// garbage and will be refused).
double absoluteTimeScale(const sensor_msgs::msg::PointCloud2& cloud, const TimeField& field) {
  const std::size_t n = static_cast<std::size_t>(cloud.width()) * cloud.height();
  const std::size_t end = (n - 1) * cloud.point_step() + field.offset + 8;
  if (n == 0 || cloud.data().size() < end) return 1.0;
  const double last = readAs<double>(cloud.data().data() + end - 8);
  const double origin = headerSeconds(cloud);
  if (std::abs(last - origin) <= kMaxTimeOffset) return 1.0;
  return std::abs(last * 1e-9 - origin) <= kMaxTimeOffset ? 1e-9 : 1.0;
}

}  // namespace

bool hasAbsoluteTimes(const sensor_msgs::msg::PointCloud2& cloud) {
  const auto* f = find(cloud, "timestamp");
  return f && f->datatype() == kFloat64;
}

void shiftAbsoluteTimes(sensor_msgs::msg::PointCloud2& cloud, double offset_s) {
  if (!hasAbsoluteTimes(cloud)) return;
  const auto* f = find(cloud, "timestamp");
  const TimeField field{"timestamp", f->offset(), kFloat64, 1.0, true};
  const double offset = offset_s / absoluteTimeScale(cloud, field);  // in the field's unit
  const std::size_t n = static_cast<std::size_t>(cloud.width()) * cloud.height();
  const std::size_t step = cloud.point_step();
  // The accessors read once: each is a call into the generated types' library.
  const std::size_t at = f->offset();
  std::uint8_t* data = cloud.data().data();
  const std::size_t size = cloud.data().size();
  for (std::size_t i = 0; i < n && (i * step + at + 8) <= size; ++i) {
    std::uint8_t* q = data + i * step + at;
    const double shifted = readAs<double>(q) + offset;
    std::memcpy(q, &shifted, 8);
  }
}

sensor_msgs::msg::PointCloud2 makeScanCloud(const ScanPoints& points, const std::string& frame_id) {
  constexpr std::uint32_t kStep = 22;
  sensor_msgs::msg::PointCloud2 cloud;
  cloud.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
                field("intensity", 12, kFloat32), field("t", 16, kFloat32), field("ring", 20, kUint16)});
  const std::size_t n = points.positions.size();
  setLayout(cloud, n, kStep, frame_id);
  std::uint8_t* out = cloud.data().data();
  for (std::size_t i = 0; i < n; ++i, out += kStep) {
    std::memcpy(out, points.positions[i].data(), 12);
    const float intensity = points.intensities.empty() ? 0.0f : points.intensities[i];
    const float t = points.time_offsets.empty() ? 0.0f : points.time_offsets[i];
    const std::uint16_t ring = points.rings.empty() ? 0 : points.rings[i];
    std::memcpy(out + 12, &intensity, 4);
    std::memcpy(out + 16, &t, 4);
    std::memcpy(out + 20, &ring, 2);
  }
  return cloud;
}

sensor_msgs::msg::PointCloud2 makeLivoxCloud(const ScanPoints& points, const std::string& frame_id,
                                             std::int64_t stamp_ns) {
  constexpr std::uint32_t kStep = 26;  // packed, as the driver's LivoxPointXyzrtlt
  sensor_msgs::msg::PointCloud2 cloud;
  cloud.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
                field("intensity", 12, kFloat32), field("tag", 16, kUint8), field("line", 17, kUint8),
                field("timestamp", 18, kFloat64)});
  setLayout(cloud, points.positions.size(), kStep, frame_id);
  builtin_interfaces::msg::Time stamp;
  stamp.sec(static_cast<std::int32_t>(stamp_ns / 1'000'000'000));
  stamp.nanosec(static_cast<std::uint32_t>(stamp_ns % 1'000'000'000));
  cloud.header().stamp(stamp);
  std::uint8_t* out = cloud.data().data();
  for (std::size_t i = 0; i < points.positions.size(); ++i, out += kStep) {
    std::memcpy(out, points.positions[i].data(), 12);
    const float intensity = points.intensities.empty() ? 0.0f : points.intensities[i];
    const std::uint8_t tag = 0;
    const auto line = static_cast<std::uint8_t>(points.rings.empty() ? 0 : points.rings[i]);
    const double t = points.time_offsets.empty() ? 0.0 : points.time_offsets[i];
    const double timestamp = static_cast<double>(stamp_ns) + t * 1e9;
    std::memcpy(out + 12, &intensity, 4);
    std::memcpy(out + 16, &tag, 1);
    std::memcpy(out + 17, &line, 1);
    std::memcpy(out + 18, &timestamp, 8);
  }
  return cloud;
}

// Packed x, y, z clouds and vectors of points have one layout: either is copied into the other whole.
static_assert(sizeof(Eigen::Vector3f) == 12, "Vector3f is three packed floats");

sensor_msgs::msg::PointCloud2 makeXyzCloud(const std::vector<Eigen::Vector3f>& points, const std::string& frame_id) {
  sensor_msgs::msg::PointCloud2 cloud;
  cloud.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32)});
  // One copy: the points are packed (x, y, z) floats, as the cloud's rows are. (A copy per point
  // through cloud.data(), an accessor of the generated types' library, cost a call per point.)
  // Filled before setLayout, whose resize then has nothing to do: no zero fill of 1.2 MB first.
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(points.data());
  cloud.data().assign(bytes, bytes + 12 * points.size());
  setLayout(cloud, points.size(), 12, frame_id);
  return cloud;
}

TimeField findTimeField(const sensor_msgs::msg::PointCloud2& cloud) {
  for (const char* name : {"t", "time", "timestamp", "offset_time"}) {
    const auto* f = find(cloud, name);
    if (!f) continue;
    switch (f->datatype()) {
      case kFloat32:
      case kFloat64:
        return {name, f->offset(), f->datatype(), 1.0, f->datatype() == kFloat64 && std::string(name) == "timestamp"};
      case kUint32:
      case kInt32:
        return {name, f->offset(), f->datatype(), 1e-9};
      default:
        throw std::runtime_error(std::string("per-point time field '") + name + "' has PointField datatype " +
                                 std::to_string(f->datatype()) +
                                 "; accepted: float32 or float64 seconds, uint32 or int32 nanoseconds");
    }
  }
  std::string present;
  for (const auto& f : cloud.fields()) present += (present.empty() ? "" : ", ") + f.name();
  throw std::runtime_error(
      "no per-point time field (looked for t, time, timestamp, offset_time; the cloud has: " + present + ")");
}

ScanPoints readCloud(const sensor_msgs::msg::PointCloud2& cloud, const TimeField* time_field) {
  if (cloud.is_bigendian()) throw std::runtime_error("big-endian point clouds are not supported");
  const std::size_t n = static_cast<std::size_t>(cloud.width()) * cloud.height();
  const std::size_t step = cloud.point_step();
  // Divided, not multiplied: width x height x point_step of a corrupt header can exceed 64 bits.
  // (A point_step of 0 is refused below, by the fields that lie beyond it.)
  if (step > 0 && cloud.data().size() / step < n) {
    throw std::runtime_error("cloud data holds " + std::to_string(cloud.data().size()) + " bytes, fewer than its " +
                             std::to_string(n) + " points of " + std::to_string(step) + " bytes need");
  }
  auto checked = [&](const char* name, bool required, std::uint8_t want) -> const sensor_msgs::msg::PointField* {
    const auto* f = find(cloud, name);
    if (!f) {
      if (required) throw std::runtime_error(std::string("cloud has no '") + name + "' field");
      return nullptr;
    }
    if (want && f->datatype() != want) {
      if (required) throw std::runtime_error(std::string("field '") + name + "' must be float32");
      return nullptr;
    }
    if (f->offset() + sizeOf(f->datatype()) > step) {
      throw std::runtime_error(std::string("field '") + name + "' lies beyond point_step");
    }
    return f;
  };
  const auto* fx = checked("x", true, kFloat32);
  const auto* fy = checked("y", true, kFloat32);
  const auto* fz = checked("z", true, kFloat32);
  const auto* fi = checked("intensity", false, kFloat32);
  const auto* fr = checked("ring", false, kUint16);
  if (time_field && time_field->offset + sizeOf(time_field->datatype) > step) {
    throw std::runtime_error("time field '" + time_field->name + "' lies beyond point_step");
  }
  double time_scale = time_field ? time_field->scale : 1.0, time_origin = 0.0;
  if (time_field && time_field->absolute) {
    time_origin = headerSeconds(cloud);
    time_scale = absoluteTimeScale(cloud, *time_field);
  }
  ScanPoints out;
  out.positions.resize(n);
  if (fi) out.intensities.resize(n);
  if (fr) out.rings.resize(n);
  if (time_field) out.time_offsets.resize(n);
  const std::uint8_t* base = cloud.data().data();
  // Offsets read once: the fields' accessors live in the generated types' library, a call each.
  const std::uint32_t x_at = fx->offset(), y_at = fy->offset(), z_at = fz->offset();
  const std::uint32_t intensity_at = fi ? fi->offset() : 0, ring_at = fr ? fr->offset() : 0;
  // A cloud of packed (x, y, z) floats and nothing else (the LO's local map, makeXyzCloud) is
  // the positions' own layout: one copy.
  if (step == 12 && x_at == 0 && y_at == 4 && z_at == 8 && !fi && !fr && !time_field) {
    if (n > 0) std::memcpy(static_cast<void*>(out.positions.data()), base, 12 * n);
    return out;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = base + i * step;
    out.positions[i] = {readAs<float>(p + x_at), readAs<float>(p + y_at), readAs<float>(p + z_at)};
    if (fi) out.intensities[i] = readAs<float>(p + intensity_at);
    if (fr) out.rings[i] = readAs<std::uint16_t>(p + ring_at);
    if (time_field) {
      const std::uint8_t* q = p + time_field->offset;
      double t = 0;
      switch (time_field->datatype) {
        case kFloat32:
          t = readAs<float>(q);
          break;
        case kFloat64:
          t = readAs<double>(q) * time_scale - time_origin;
          break;
        case kUint32:
          t = readAs<std::uint32_t>(q) * time_field->scale;
          break;
        case kInt32:
          t = readAs<std::int32_t>(q) * time_field->scale;
          break;
      }
      // Also keeps t within float's range: converting a larger double to float is undefined.
      out.time_offsets[i] = std::abs(t) <= kMaxTimeOffset ? static_cast<float>(t) : std::nanf("");
    }
  }
  return out;
}

}  // namespace uampc::pointcloud
