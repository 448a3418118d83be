// Surface normals of the local map, estimated on the panoramic depth map.
//
// Why from the depth map and not by PCA of k nearest neighbours in the local map: building a k-d
// tree over a 100k-point local map and running 100k neighbour queries costs tens of milliseconds,
// the whole control step has a 5 ms budget. The panorama is an organised grid, so the neighbours
// of a pixel are free, and only the points that the LiDAR rays of U(theta) actually hit need a
// normal; they are computed on demand and cached for the rest of the control step.
//
// The normal of a local-map point is the area-weighted normal of the fan of triangles it forms
// with its 8 ring neighbours (a Newell-style sum of cross products of consecutive neighbour
// offsets, as in organised-cloud normal estimation), found around the point's own pixel (where
// Eq. 5 puts it, also when a nearer point's splat covers that pixel), whichever pixel of its splat
// a ray reached: so a point has one normal, however the rays reach it. The neighbour in each
// direction is the first pixel, at most neighbour_reach_px away, holding a different local-map
// point than the centre (skipping empty pixels and the centre point's own splat, see
// PanoramicDepthMap); a neighbour whose range differs from the centre's by more than
// max_range_jump_ratio is on another surface (occluding or occluded) and is not used. The
// normal is rejected when too few neighbours remain or when a neighbour lies off the fitted plane
// by more than max_off_plane_ratio of its distance (edges, corners, clutter): like the LO, which
// only builds point-to-plane residuals on planar patches.
//
// Normals are unit vectors in the base frame (base axes), oriented towards the base origin.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "uampc/mpc/panoramic_depth_map.hpp"

namespace uampc::mpc {

class DepthMapNormals {
 public:
  struct Config {
    int neighbour_reach_px = 6;          // how far to look for a neighbour in each of 8 directions
    double max_range_jump_ratio = 0.3;   // |r_neighbour - r_centre| <= ratio * r_centre
    double max_off_plane_ratio = 0.25;   // |n . (q - c)| <= ratio * |q - c| for every neighbour
    int min_triangles = 2;               // fan triangles needed for a normal
  };

  DepthMapNormals();  // default Config
  explicit DepthMapNormals(const Config& config);

  // Starts a new control step on a freshly rendered map; forgets the cached normals. The map must
  // outlive every later call to normal().
  void reset(const PanoramicDepthMap& map);

  // Unit normal (base axes) of the surface at an occupied pixel, or nullptr when the pixel is
  // empty or no reliable normal can be estimated there. Cached per local-map point (estimated at
  // that point's own pixel, whichever of its pixels asked) until the next reset().
  // Inline: called once per ray and candidate angle, and nearly always answered by the cache.
  const Eigen::Vector3f* normal(int pixel) {
    if (map_ == nullptr) throwNotReset();
    // Cached per local-map point, not per pixel: a splatted point covers many pixels. The point
    // is named by its centre pixel, so the cache is as large as the panorama, not as the local
    // map, and the rays that sweep the panorama find it in nearby memory.
    const std::int32_t centre = map_->centrePixel(pixel);
    if (centre < 0) return nullptr;
    CachedNormal& cached = cache_[centre];
    if (cached.generation != generation_) {  // not asked since reset(): unknown
      cached.generation = generation_;
      cached.state = compute(centre, &cached.normal);
    }
    return cached.state == kValid ? &cached.normal : nullptr;
  }

  // The same estimate without the cache, for the point whose own pixel is centre_pixel (a
  // PanoramicDepthMap::centrePixel()); returns false when there is no reliable normal.
  bool estimate(const PanoramicDepthMap& map, std::int32_t centre_pixel, Eigen::Vector3f* normal_B) const;

  // Number of normals computed since the last reset (valid or not): a cost indicator.
  int computedCount() const { return computed_count_; }

 private:
  enum State : std::uint8_t { kUnknown = 0, kValid = 1, kInvalid = 2 };

  // Normal and state side by side: one cache line per look-up. An entry counts only if its
  // generation is the current one, so reset() forgets every normal by counting up instead of
  // rewriting the whole cache (1 MB for a 1-degree panorama, every control step); it rewrites it
  // when the count wraps, once in 65535 resets.
  struct CachedNormal {
    Eigen::Vector3f normal;
    State state;
    std::uint16_t generation;
  };

  [[noreturn]] static void throwNotReset();
  State compute(std::int32_t centre_pixel, Eigen::Vector3f* normal);  // estimate() into the cache

  Config config_;
  const PanoramicDepthMap* map_ = nullptr;
  std::vector<CachedNormal> cache_;  // per local-map point, indexed by its centre pixel
  std::uint16_t generation_ = 0;     // of the current reset(); entries of other ones are stale
  int computed_count_ = 0;
};

}  // namespace uampc::mpc
