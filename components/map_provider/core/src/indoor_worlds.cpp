// Indoor worlds: the long corridor and the multi-storey building with a stairwell.
#include <cmath>

#include "uampc/world/procedural_worlds.hpp"

namespace uampc::world {

TriangleMesh makeCorridor(const CorridorConfig& config) {
  TriangleMesh mesh;
  const float L = static_cast<float>(config.length);
  const float w = 0.5f * static_cast<float>(config.width);
  const float h = static_cast<float>(config.height);
  const float t = 0.2f;                                 // wall thickness
  mesh.addBox({-t, -w - t, -t}, {L + t, w + t, 0.0f});  // floor
  mesh.addBox({-t, -w - t, h}, {L + t, w + t, h + t});  // ceiling
  mesh.addBox({-t, -w - t, 0.0f}, {L + t, -w, h});      // right wall
  mesh.addBox({-t, w, 0.0f}, {L + t, w + t, h});        // left wall
  mesh.addBox({-t, -w, 0.0f}, {0.0f, w, h});            // start wall
  mesh.addBox({L, -w, 0.0f}, {L + t, w, h});            // end wall
  if (config.door_spacing > 0.0) {
    // Door frames standing 0.1 m out of the walls, alternating sides.
    int k = 0;
    for (double x = config.door_spacing; x < config.length - 1.0; x += config.door_spacing, ++k) {
      const float xf = static_cast<float>(x);
      const float y0 = (k % 2 == 0) ? -w : w - 0.1f;
      mesh.addBox({xf - 0.6f, y0, 0.0f}, {xf - 0.5f, y0 + 0.1f, 2.2f});
      mesh.addBox({xf + 0.5f, y0, 0.0f}, {xf + 0.6f, y0 + 0.1f, 2.2f});
      mesh.addBox({xf - 0.6f, y0, 2.1f}, {xf + 0.6f, y0 + 0.1f, 2.2f});
    }
  }
  return mesh;
}

std::vector<Eigen::Vector3d> corridorWaypoints(const CorridorConfig& config, double base_height) {
  return {{2.0, 0.0, base_height}, {config.length - 2.0, 0.0, base_height}};
}

namespace {

struct StairwellGeometry {
  float xa, xb;  // the stairwell spans x in [xa, L]; landings start at xb
  float sw;      // stairwell width, along y from 0
};

StairwellGeometry stairwell(const MultilevelConfig& c) {
  const float L = static_cast<float>(c.length);
  return {L - static_cast<float>(c.stairwell_length), L - 1.2f,
          static_cast<float>(c.stairwell_width)};
}

}  // namespace

TriangleMesh makeMultilevel(const MultilevelConfig& config) {
  TriangleMesh mesh;
  const float L = static_cast<float>(config.length);
  const float W = static_cast<float>(config.width);
  const float fh = static_cast<float>(config.floor_height);
  const float slab = static_cast<float>(config.slab_thickness);
  const float top = fh * static_cast<float>(config.floors);
  const float m = static_cast<float>(config.ground_margin);
  const float wall = 0.3f;
  const StairwellGeometry s = stairwell(config);

  mesh.addGroundRectangle(-m, -m, L + m, W + m, 0.0f);
  // Outer walls, with a door gap in the west wall at ground level.
  mesh.addBox({-wall, -wall, 0.0f}, {L + wall, 0.0f, top});
  mesh.addBox({-wall, W, 0.0f}, {L + wall, W + wall, top});
  mesh.addBox({L, 0.0f, 0.0f}, {L + wall, W, top});
  mesh.addBox({-wall, 0.0f, 0.0f}, {0.0f, 0.5f * W - 1.0f, top});
  mesh.addBox({-wall, 0.5f * W + 1.0f, 0.0f}, {0.0f, W, top});
  mesh.addBox({-wall, 0.5f * W - 1.0f, 2.2f}, {0.0f, 0.5f * W + 1.0f, top});
  // Floor slabs with the stairwell left open, and the roof.
  for (int k = 1; k <= config.floors; ++k) {
    const float z = fh * static_cast<float>(k);
    if (k == config.floors) {
      mesh.addBox({0.0f, 0.0f, z}, {L, W, z + slab});
      continue;
    }
    mesh.addBox({0.0f, 0.0f, z - slab}, {s.xa, W, z});
    mesh.addBox({s.xa, s.sw, z - slab}, {L, W, z});
  }
  // Interior columns, floor to ceiling, kept off the stairwell.
  const float cs = static_cast<float>(config.column_spacing);
  for (int k = 0; k < config.floors; ++k) {
    const float z0 = fh * static_cast<float>(k);
    for (float x = cs; x < L - 1.0f; x += cs) {
      for (float y = cs; y < W - 1.0f; y += cs) {
        if (x > s.xa - 2.0f) continue;
        mesh.addBox({x - 0.2f, y - 0.2f, z0}, {x + 0.2f, y + 0.2f, z0 + fh - slab});
      }
    }
  }
  // Switch-back stairs: half a storey along +x in y in [0, sw/2], a landing, half along -x.
  const int steps = static_cast<int>(std::ceil(0.5f * fh / 0.18f));
  const float rise = 0.5f * fh / static_cast<float>(steps);
  const float run = (s.xb - s.xa) / static_cast<float>(steps);
  for (int k = 0; k + 1 < config.floors; ++k) {
    const float z0 = fh * static_cast<float>(k);
    for (int i = 0; i < steps; ++i) {
      const float up = z0 + rise * static_cast<float>(i + 1);
      mesh.addBox({s.xa + run * static_cast<float>(i), 0.0f, z0},
                  {s.xa + run * static_cast<float>(i + 1), 0.5f * s.sw, up});
      const float up2 = z0 + 0.5f * fh + rise * static_cast<float>(i + 1);
      mesh.addBox({s.xb - run * static_cast<float>(i + 1), 0.5f * s.sw, z0},
                  {s.xb - run * static_cast<float>(i), s.sw, up2});
    }
    mesh.addBox({s.xb, 0.0f, z0 + 0.5f * fh - slab}, {L, s.sw, z0 + 0.5f * fh});
  }
  return mesh;
}

std::vector<Eigen::Vector3d> multilevelWaypoints(const MultilevelConfig& config,
                                                 double base_height) {
  const StairwellGeometry s = stairwell(config);
  const double W = config.width, fh = config.floor_height;
  const double q1 = 0.25 * s.sw, q3 = 0.75 * s.sw;
  std::vector<Eigen::Vector3d> w;
  for (int k = 0; k < config.floors; ++k) {
    const double z = fh * k + base_height;
    w.emplace_back(3.0, q3, z);
    w.emplace_back(3.0, W - 3.0, z);
    w.emplace_back(s.xa - 1.5, W - 3.0, z);
    if (k + 1 == config.floors) break;
    w.emplace_back(s.xa - 1.5, q1, z);
    w.emplace_back(s.xa + 0.2, q1, z);
    w.emplace_back(s.xb + 0.6, q1, z + 0.5 * fh);
    w.emplace_back(s.xb + 0.6, q3, z + 0.5 * fh);
    w.emplace_back(s.xa - 0.5, q3, z + fh);
  }
  return w;
}

}  // namespace uampc::world
