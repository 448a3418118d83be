// Indoor worlds: the long corridor and the multi-storey building with a stairwell.
#include <algorithm>
#include <cmath>
#include <vector>

#include "uampc/world/procedural_worlds.hpp"

namespace uampc::world {

namespace {

// One long side wall of the corridor at y = face (its inner face), thickness `thick` outwards
// (sign = -1: towards -y), with a door recess centred at every x in doors: a gap in the wall up to
// the door's height, closed at the back by the door leaf. The gap's sides are the wall's ends:
// surfaces facing along the corridor, which is what fixes the position along it.
void addSideWall(TriangleMesh& mesh, const CorridorConfig& c, float face, float sign, const std::vector<float>& doors) {
  const float L = static_cast<float>(c.length), h = static_cast<float>(c.height), t = 0.2f;
  const float depth = static_cast<float>(c.door_depth), half = 0.5f * static_cast<float>(c.door_width);
  const float door_h = static_cast<float>(c.door_height);
  const float thick = doors.empty() ? t : depth;  // a plain wall keeps the plain thickness
  const auto slab = [&](float x0, float x1, float y_in, float y_out, float z0, float z1) {
    mesh.addBox({x0, std::min(y_in, y_out), z0}, {x1, std::max(y_in, y_out), z1});
  };
  float x = -t;
  for (float d : doors) {
    slab(x, d - half, face, face + sign * thick, 0.0f, h);                       // wall up to the door
    slab(d - half, d + half, face, face + sign * thick, door_h, h);              // lintel
    slab(d - half, d + half, face + sign * thick, face + sign * (thick + t), 0.0f, door_h);  // door leaf
    x = d + half;
  }
  slab(x, L + t, face, face + sign * thick, 0.0f, h);
}

}  // namespace

TriangleMesh makeCorridor(const CorridorConfig& config) {
  TriangleMesh mesh;
  const float L = static_cast<float>(config.length);
  const float w = 0.5f * static_cast<float>(config.width);
  const float h = static_cast<float>(config.height);
  const float t = 0.2f;                                 // wall thickness
  mesh.addBox({-t, -w - t, -t}, {L + t, w + t, 0.0f});  // floor
  mesh.addBox({-t, -w - t, h}, {L + t, w + t, h + t});  // ceiling
  mesh.addBox({-t, -w, 0.0f}, {0.0f, w, h});            // start wall
  mesh.addBox({L, -w, 0.0f}, {L + t, w, h});            // end wall
  // Doors every door_spacing metres on alternating sides, none within 2 m of the ends.
  std::vector<float> right, left;
  if (config.door_spacing > 0.0) {
    int k = 0;
    for (double x = config.door_spacing; x < config.length - 2.0; x += config.door_spacing, ++k) {
      (k % 2 == 0 ? right : left).push_back(static_cast<float>(x));
    }
  }
  addSideWall(mesh, config, -w, -1.0f, right);
  addSideWall(mesh, config, w, 1.0f, left);
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
  // Switch-back stairs: half a storey along +x in y in [0, sw/2], a landing, half along -x. Each
  // flight is a sloped slab with the steps on top (waist 0.3 m below each tread), open beneath, as
  // concrete stairs are: solid blocks down to the floor walled the lower flight in on every side
  // within the LiDAR's minimum range and left it blind for two seconds.
  const int steps = static_cast<int>(std::ceil(0.5f * fh / 0.18f));
  const float rise = 0.5f * fh / static_cast<float>(steps);
  const float run = (s.xb - s.xa) / static_cast<float>(steps);
  const float waist = 0.3f;
  for (int k = 0; k + 1 < config.floors; ++k) {
    const float z0 = fh * static_cast<float>(k);
    for (int i = 0; i < steps; ++i) {
      const float up = z0 + rise * static_cast<float>(i + 1);
      mesh.addBox({s.xa + run * static_cast<float>(i), 0.0f, std::max(z0, up - waist)},
                  {s.xa + run * static_cast<float>(i + 1), 0.5f * s.sw, up});
      const float up2 = z0 + 0.5f * fh + rise * static_cast<float>(i + 1);
      mesh.addBox({s.xb - run * static_cast<float>(i + 1), 0.5f * s.sw, up2 - waist},
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
