// The campus: a grid of blocks, rich ones (buildings with facade detail, trees, poles, low walls)
// and a row of poor ones (plain walls or lawn), separated by streets that a loop can follow.
#include <algorithm>
#include <cmath>

#include "uampc/world/procedural_worlds.hpp"
#include "uampc/world/seeded_random.hpp"

namespace uampc::world {
namespace {

using Eigen::Vector3f;

struct Rect {  // axis-aligned footprint
  float x0, y0, x1, y1;
  bool overlaps(const Rect& o, float gap) const {
    return x0 - gap < o.x1 && o.x0 - gap < x1 && y0 - gap < o.y1 && o.y0 - gap < y1;
  }
  bool contains(float x, float y, float gap) const {
    return x > x0 - gap && x < x1 + gap && y > y0 - gap && y < y1 + gap;
  }
};

// A building: a box with pilasters on every facade and a ledge at every floor.
void addBuilding(TriangleMesh& mesh, const Rect& r, float height, SeededRandom& random) {
  mesh.addBox({r.x0, r.y0, 0.0f}, {r.x1, r.y1, height});
  const float pilaster_spacing = static_cast<float>(random.uniform(3.0, 6.0));
  const float depth = static_cast<float>(random.uniform(0.2, 0.5));
  const float floor_height = 3.5f;
  // Facades as (start, direction, length, outward normal).
  const struct {
    Vector3f start, dir, out;
    float length;
  } facades[] = {
      {{r.x0, r.y0, 0}, {1, 0, 0}, {0, -1, 0}, r.x1 - r.x0},
      {{r.x1, r.y0, 0}, {0, 1, 0}, {1, 0, 0}, r.y1 - r.y0},
      {{r.x1, r.y1, 0}, {-1, 0, 0}, {0, 1, 0}, r.x1 - r.x0},
      {{r.x0, r.y1, 0}, {0, -1, 0}, {-1, 0, 0}, r.y1 - r.y0},
  };
  for (const auto& f : facades) {
    const int n = static_cast<int>(f.length / pilaster_spacing);
    for (int k = 1; k < n; ++k) {
      const Vector3f c = f.start + f.dir * (f.length * k / n) + f.out * (0.5f * depth);
      const Vector3f half = f.dir.cwiseAbs() * 0.25f + f.out.cwiseAbs() * (0.5f * depth);
      mesh.addBox(c - half, c + half + Vector3f(0, 0, height));
    }
    for (float z = floor_height; z < height - 0.5f; z += floor_height) {
      const Vector3f a = f.start + Vector3f(0, 0, z);
      const Vector3f b = a + f.dir * f.length + f.out * 0.3f + Vector3f(0, 0, 0.25f);
      mesh.addBox(a.cwiseMin(b), a.cwiseMax(b));
    }
  }
  // Parapet on the roof.
  if (random.chance(0.5)) {
    mesh.addBox({r.x0, r.y0, height}, {r.x1, r.y0 + 0.3f, height + 1.0f});
    mesh.addBox({r.x0, r.y1 - 0.3f, height}, {r.x1, r.y1, height + 1.0f});
  }
}

void addTree(TriangleMesh& mesh, float x, float y, SeededRandom& random, int segments) {
  const float trunk_height = static_cast<float>(random.uniform(1.8, 3.2));
  const float crown_radius = static_cast<float>(random.uniform(1.2, 2.8));
  const float crown_height = static_cast<float>(random.uniform(2.0, 4.5));
  mesh.addCylinder({x, y, 0.0f}, static_cast<float>(random.uniform(0.12, 0.3)), trunk_height + 0.5f,
                   segments);
  const Vector3f widest(x, y, trunk_height + 0.35f * crown_height);
  mesh.addCone(widest, crown_radius, -0.35f * crown_height, segments);  // lower part
  mesh.addCone(widest, crown_radius, 0.65f * crown_height, segments);   // upper part
}

void addPole(TriangleMesh& mesh, float x, float y, int segments) {
  mesh.addCylinder({x, y, 0.0f}, 0.1f, 6.0f, segments);
  mesh.addBox({x - 0.05f, y - 0.05f, 5.8f}, {x + 1.2f, y + 0.05f, 5.9f});
}

void addRichBlock(TriangleMesh& mesh, const Rect& block, const CampusConfig& config,
                  SeededRandom& random) {
  std::vector<Rect> buildings;
  for (int attempt = 0; attempt < 30 && buildings.size() < 4; ++attempt) {
    const float w = static_cast<float>(random.uniform(10.0, 28.0));
    const float d = static_cast<float>(random.uniform(10.0, 28.0));
    const float x = static_cast<float>(random.uniform(block.x0 + 3.0, block.x1 - 3.0 - w));
    const float y = static_cast<float>(random.uniform(block.y0 + 3.0, block.y1 - 3.0 - d));
    const Rect r{x, y, x + w, y + d};
    if (r.x1 > block.x1 - 3.0f || r.y1 > block.y1 - 3.0f) continue;
    if (std::any_of(buildings.begin(), buildings.end(),
                    [&](const Rect& o) { return o.overlaps(r, 5.0f); })) {
      continue;
    }
    buildings.push_back(r);
    addBuilding(mesh, r, 3.5f * static_cast<float>(random.integer(2, 7)), random);
  }
  // Trees inside the block, away from buildings.
  const int trees = random.integer(4, 10);
  for (int k = 0; k < trees; ++k) {
    const float x = static_cast<float>(random.uniform(block.x0 + 2.0, block.x1 - 2.0));
    const float y = static_cast<float>(random.uniform(block.y0 + 2.0, block.y1 - 2.0));
    if (std::any_of(buildings.begin(), buildings.end(),
                    [&](const Rect& o) { return o.contains(x, y, 3.0f); })) {
      continue;
    }
    addTree(mesh, x, y, random, config.segments);
  }
  // Street trees on the sidewalk, 1.5 m outside the block edge.
  const float s = static_cast<float>(config.tree_spacing);
  for (float t = block.x0 + 0.5f * s; t < block.x1; t += s) {
    addTree(mesh, t + static_cast<float>(random.uniform(-1.0, 1.0)), block.y0 - 1.5f, random,
            config.segments);
    addTree(mesh, t + static_cast<float>(random.uniform(-1.0, 1.0)), block.y1 + 1.5f, random,
            config.segments);
  }
  // A low wall with gaps along one edge of the block.
  if (random.chance(0.6)) {
    const float y = random.chance(0.5) ? block.y0 + 0.5f : block.y1 - 0.8f;
    for (float x = block.x0 + 1.0f; x < block.x1 - 4.0f; x += 8.0f) {
      mesh.addBox({x, y, 0.0f}, {x + 6.0f, y + 0.3f, static_cast<float>(random.uniform(0.8, 1.6))});
    }
  }
}

// Poor geometry: plain smooth walls along the block's edges, or nothing at all.
void addPoorBlock(TriangleMesh& mesh, const Rect& block, SeededRandom& random) {
  if (random.chance(0.25)) return;  // lawn
  const float h = static_cast<float>(random.uniform(2.5, 4.0));
  mesh.addBox({block.x0, block.y0, 0.0f}, {block.x1, block.y0 + 0.3f, h});
  mesh.addBox({block.x0, block.y1 - 0.3f, 0.0f}, {block.x1, block.y1, h});
  if (random.chance(0.5)) mesh.addBox({block.x0, block.y0, 0.0f}, {block.x0 + 0.3f, block.y1, h});
  if (random.chance(0.5)) mesh.addBox({block.x1 - 0.3f, block.y0, 0.0f}, {block.x1, block.y1, h});
}

float blockCentre(const CampusConfig& c, int i) {
  return static_cast<float>((i - 0.5 * (c.blocks - 1)) * (c.block_size + c.street_width));
}

}  // namespace

TriangleMesh makeCampus(const CampusConfig& config, std::uint64_t seed) {
  SeededRandom random(seed);
  TriangleMesh mesh;
  const float pitch = static_cast<float>(config.block_size + config.street_width);
  const float extent = 0.5f * config.blocks * pitch + static_cast<float>(config.margin);
  mesh.addGroundRectangle(-extent, -extent, extent, extent, 0.0f);
  const float half = 0.5f * static_cast<float>(config.block_size);
  for (int j = 0; j < config.blocks; ++j) {
    for (int i = 0; i < config.blocks; ++i) {
      const float cx = blockCentre(config, i), cy = blockCentre(config, j);
      const Rect block{cx - half, cy - half, cx + half, cy + half};
      if (j >= config.blocks - config.poor_rows) {
        addPoorBlock(mesh, block, random);
        continue;
      }
      addRichBlock(mesh, block, config, random);
      // Street-light poles, 1 m outside the block's south and west edges.
      const float s = static_cast<float>(config.pole_spacing);
      for (float t = block.x0 + 2.0f; t < block.x1; t += s) {
        addPole(mesh, t, block.y0 - 1.0f, config.segments);
      }
      for (float t = block.y0 + 2.0f; t < block.y1; t += s) {
        addPole(mesh, block.x0 - 1.0f, t, config.segments);
      }
    }
  }
  return mesh;
}

std::vector<Eigen::Vector3d> campusLoopWaypoints(const CampusConfig& config, double base_height) {
  // Around the centre block and the poor row north of it: half rich, half poor stretches.
  const double pitch = config.block_size + config.street_width;
  const int centre = config.blocks / 2;
  const double x0 = blockCentre(config, centre) - 0.5 * pitch;
  const double x1 = blockCentre(config, centre) + 0.5 * pitch;
  const double y0 = blockCentre(config, centre) - 0.5 * pitch;
  const double y1 = blockCentre(config, config.blocks - 1) + 0.5 * pitch;
  return {
      {x0, y0, base_height}, {x1, y0, base_height}, {x1, y1, base_height}, {x0, y1, base_height}};
}

}  // namespace uampc::world
