// The world as Embree sees it: built once, then queried by many rays.
//
// Triangles are cast against exactly. A point map has no surfaces, so each of its points becomes
// a splat: a disc of radius point_radius centred on the point and facing the ray (Embree's disc
// points), hit at the point's own depth, as the reference simulator draws each map point as a
// screen-facing square at its depth. A ray hits the nearest splat it passes within point_radius
// of; with the reference's radius, 0.55 sqrt(3) times the map's resolution, neighbouring splats
// overlap and rays do not slip between them. docs/decisions/point-map-splats.md says where this
// departs from the reference.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "uampc/world/triangle_mesh.hpp"

namespace uampc::raycaster {

struct Hit {
  bool valid = false;
  float distance = 0.0f;                             // m along the (unit) direction
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, facing against the ray
};

struct Ray {
  Eigen::Vector3f origin;
  Eigen::Vector3f direction;  // unit
  float max_distance;
};

class RayCastScene {
 public:
  // Throws std::runtime_error if Embree fails or the world holds nothing. point_radius: each point's
// splat, m.
  // build_threads: threads Embree may use to build its BVH (queries always run on the caller's).
  RayCastScene(const world::TriangleMesh& mesh, const std::vector<Eigen::Vector3f>& points = {},
               float point_radius = 0.05f, int build_threads = 1);
  ~RayCastScene();
  RayCastScene(RayCastScene&&) noexcept;
  RayCastScene& operator=(RayCastScene&&) noexcept;
  RayCastScene(const RayCastScene&) = delete;
  RayCastScene& operator=(const RayCastScene&) = delete;

  // First hit along one ray, from its origin up to max_distance.
  Hit intersect(const Ray& ray) const;

  // Many rays, in packets of kPacketSize (faster for bundles of rays from one origin);
  // hits.size() == rays.size() afterwards, hits[k] for rays[k]. `order`, if not empty, is a
  // permutation of the rays' indices: each packet takes the next kPacketSize of it. Packets of
  // nearly parallel rays are traversed faster (RayCaster groups a pattern's rays by laser).
  // 8 rays: an AVX2 register's width of floats. Packets of 16 are emulated on AVX2 and cost more:
  // a Mid-360 frame's intersections took 2.15-2.27 ms in packets of 16 against 1.91-1.93 ms in
  // packets of 8 (`raycaster_core_bench` BM_SceneIntersectOnly/2, one core, three alternating
  // rounds, 2026-11-28); the hits are the same.
  static constexpr std::size_t kPacketSize = 8;
  void intersect(const std::vector<Ray>& rays, std::vector<Hit>& hits,
                 const std::vector<std::uint32_t>& order = {}) const;

  std::size_t triangleCount() const { return triangles_; }
  std::size_t pointCount() const { return points_; }

 private:
  struct Embree;
  std::unique_ptr<Embree> embree_;
  std::size_t triangles_ = 0;
  std::size_t points_ = 0;
};

}  // namespace uampc::raycaster
