#include "uampc/world/density_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "uampc/world/seeded_random.hpp"
#include "uampc/world/short_number.hpp"

namespace uampc::world {
const char* toString(StretchKind kind) {
  switch (kind) {
    case StretchKind::kBuiltUp:
      return "built-up";
    case StretchKind::kLawn:
      return "lawn";
    case StretchKind::kCarPark:
      return "car park";
    case StretchKind::kOneWall:
      return "one wall";
    case StretchKind::kStreet:
      return "street";
  }
  return "?";
}

double openFractionOfProfile(const std::string& name) {
  std::string known;
  for (const auto& profile : kDensityProfiles) {
    if (name == profile.name) return profile.open_fraction;
    known += (known.empty() ? "" : ", ") + std::string(profile.name);
  }
  throw std::invalid_argument("unknown density profile '" + name + "' (known: " + known + ")");
}

void checkDensityProfile(const DensityProfileConfig& config) {
  if (!(config.open_fraction >= 0.0 && config.open_fraction <= 1.0)) {
    throw std::invalid_argument("open_fraction must be between 0 and 1 (the share of path length that is open), got " +
                                shortNumber(config.open_fraction));
  }
  if (!(config.min_stretch > 0.0 && config.max_stretch >= config.min_stretch)) {
    throw std::invalid_argument("density profile: stretch lengths need 0 < min_stretch <= max_stretch, got " +
                                shortNumber(config.min_stretch) + " and " + shortNumber(config.max_stretch));
  }
}

std::vector<PathStretch> drawStretches(double path_length, const DensityProfileConfig& config, std::uint64_t seed) {
  checkDensityProfile(config);
  // A stream of its own: the objects' stream stays as it was, so a rich world is unchanged.
  SeededRandom random(mixSeed(seed, 0x5472657463686573ull));  // "Stretches"
  std::vector<PathStretch> stretches;
  double begin = 0.0;
  do {  // at least one stretch, even for a path of one sample
    PathStretch s;
    s.begin = begin;
    s.end = std::min(path_length, begin + random.uniform(config.min_stretch, config.max_stretch));
    // Both draws are made for every stretch, so one stretch's kind never shifts the next ones'.
    // The first stretch is built-up: a run starts where the LO has a map to initialise on, as a
    // recording starts where its rig can (a start on a lawn loses every controller at once).
    const bool open = random.chance(config.open_fraction) && !stretches.empty();
    const int open_kind = random.integer(0, 3);
    if (open) {
      static constexpr StretchKind kOpenKinds[] = {StretchKind::kLawn, StretchKind::kCarPark, StretchKind::kOneWall,
                                                   StretchKind::kStreet};
      s.kind = kOpenKinds[open_kind];
    }
    stretches.push_back(s);
    begin = s.end;
  } while (begin < path_length);
  return stretches;
}

}  // namespace uampc::world
