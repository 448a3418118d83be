// The only file that talks to Embree.
#include "uampc/raycaster/ray_cast_scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace uampc::raycaster {
namespace {

void check(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(error)) + ")");
  }
}

Hit toHit(float tfar, float nx, float ny, float nz, const Eigen::Vector3f& direction) {
  Hit hit;
  hit.valid = true;
  hit.distance = tfar;
  hit.normal = Eigen::Vector3f(nx, ny, nz);
  const float norm = hit.normal.norm();
  hit.normal = norm > 0.0f ? Eigen::Vector3f(hit.normal / norm) : Eigen::Vector3f(-direction);
  if (hit.normal.dot(direction) > 0.0f) hit.normal = -hit.normal;
  return hit;
}

}  // namespace

struct RayCastScene::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayCastScene::RayCastScene(const world::TriangleMesh& mesh, const std::vector<Eigen::Vector3f>& points,
                           float point_radius, int build_threads)
    : embree_(std::make_unique<Embree>()) {
  if (mesh.empty() && points.empty()) throw std::runtime_error("RayCastScene: empty world");
  const std::string config = "threads=" + std::to_string(std::max(1, build_threads));
  embree_->device = rtcNewDevice(config.c_str());
  if (!embree_->device) throw std::runtime_error("Embree: cannot create a device");
  RTCDevice device = embree_->device;
  embree_->scene = rtcNewScene(device);
  check(device, "rtcNewScene");
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

  if (!mesh.empty()) {
    const std::size_t nv = mesh.vertices.size();
    for (const auto& t : mesh.triangles) {
      if (t.minCoeff() < 0 || static_cast<std::size_t>(t.maxCoeff()) >= nv) {
        throw std::runtime_error("RayCastScene: triangle index out of range");
      }
    }
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.triangles.size()));
    check(device, "allocating triangle buffers");
    for (std::size_t i = 0; i < nv; ++i) {
      v[3 * i] = mesh.vertices[i].x();
      v[3 * i + 1] = mesh.vertices[i].y();
      v[3 * i + 2] = mesh.vertices[i].z();
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    triangles_ = mesh.triangles.size();
  }
  if (!points.empty()) {
    // A ray-facing disc at the point's own depth, as the reference simulator draws a map point as a
    // screen-facing splat (docs/decisions/point-map-splats.md).
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_DISC_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                          4 * sizeof(float), points.size()));
    check(device, "allocating point buffers");
    for (std::size_t i = 0; i < points.size(); ++i) {
      v[4 * i] = points[i].x();
      v[4 * i + 1] = points[i].y();
      v[4 * i + 2] = points[i].z();
      v[4 * i + 3] = point_radius;
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    points_ = points.size();
  }
  rtcCommitScene(embree_->scene);
  check(device, "building the scene");
}

RayCastScene::~RayCastScene() = default;
RayCastScene::RayCastScene(RayCastScene&&) noexcept = default;
RayCastScene& RayCastScene::operator=(RayCastScene&&) noexcept = default;

Hit RayCastScene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x();
  rh.ray.org_y = ray.origin.y();
  rh.ray.org_z = ray.origin.z();
  rh.ray.dir_x = ray.direction.x();
  rh.ray.dir_y = ray.direction.y();
  rh.ray.dir_z = ray.direction.z();
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = ray.max_distance;
  rh.ray.time = 0.0f;
  rh.ray.mask = std::numeric_limits<unsigned>::max();
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return toHit(rh.ray.tfar, rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z, ray.direction);
}

void RayCastScene::intersect(const std::vector<Ray>& rays, std::vector<Hit>& hits,
                             const std::vector<std::uint32_t>& order) const {
  if (!order.empty() && order.size() != rays.size()) {
    throw std::invalid_argument("RayCastScene::intersect: the order has " + std::to_string(order.size()) +
                                " indices for " + std::to_string(rays.size()) + " rays");
  }
  auto index = [&](std::size_t i) -> std::size_t { return order.empty() ? i : order[i]; };
  hits.assign(rays.size(), Hit{});
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  static_assert(kPacketSize == 8, "rtcIntersect8");
  alignas(64) RTCRayHit8 packet{};
  alignas(64) int valid[kPacketSize] = {};
  for (std::size_t first = 0; first < rays.size(); first += kPacketSize) {
    const std::size_t count = std::min(kPacketSize, rays.size() - first);
    for (std::size_t j = 0; j < kPacketSize; ++j) {
      if (j >= count) {
        valid[j] = 0;
        continue;
      }
      const Ray& r = rays[index(first + j)];
      valid[j] = -1;
      packet.ray.org_x[j] = r.origin.x();
      packet.ray.org_y[j] = r.origin.y();
      packet.ray.org_z[j] = r.origin.z();
      packet.ray.dir_x[j] = r.direction.x();
      packet.ray.dir_y[j] = r.direction.y();
      packet.ray.dir_z[j] = r.direction.z();
      packet.ray.tnear[j] = 0.0f;
      packet.ray.tfar[j] = r.max_distance;
      packet.ray.time[j] = 0.0f;
      packet.ray.mask[j] = std::numeric_limits<unsigned>::max();
      packet.ray.id[j] = static_cast<unsigned>(j);
      packet.ray.flags[j] = 0;
      packet.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, embree_->scene, &context, &packet);
    for (std::size_t j = 0; j < count; ++j) {
      if (packet.hit.geomID[j] == RTC_INVALID_GEOMETRY_ID) continue;
      const std::size_t k = index(first + j);
      hits[k] = toHit(packet.ray.tfar[j], packet.hit.Ng_x[j], packet.hit.Ng_y[j], packet.hit.Ng_z[j], rays[k].direction);
    }
  }
}

}  // namespace uampc::raycaster
