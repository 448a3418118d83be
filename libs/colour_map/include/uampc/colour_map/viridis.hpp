// matplotlib's viridis (perceptually uniform, readable in grey), dark blue to bright yellow, at
// five stops interpolated linearly: the one table the panorama snapshots and the report's heat
// maps share.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace uampc::colour_map {

// s in [0, 1] (clamped; NaN is 0): 0 is dark blue (#440154), 1 bright yellow (#fde725).
inline std::array<std::uint8_t, 3> viridis(double s) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  const double x = std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<std::uint8_t, 3> rgb{};
  for (std::size_t k = 0; k < 3; ++k) {
    rgb[k] = static_cast<std::uint8_t>(std::lround(kStops[i][k] + f * (kStops[i + 1][k] - kStops[i][k])));
  }
  return rgb;
}

}  // namespace uampc::colour_map
