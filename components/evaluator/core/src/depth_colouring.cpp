#include "uampc/evaluator/depth_colouring.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace uampc::evaluator {

namespace {

// Five stops of matplotlib's viridis (perceptually uniform, readable in grey), dark to bright.
constexpr std::array<std::array<double, 3>, 5> kViridis = {{
    {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};

std::array<std::uint8_t, 3> viridis(double s) {  // s in [0, 1]
  const double x = std::clamp(s, 0.0, 1.0) * (kViridis.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), kViridis.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<std::uint8_t, 3> c{};
  for (int k = 0; k < 3; ++k) {
    c[k] = static_cast<std::uint8_t>(std::lround(kViridis[i][k] + f * (kViridis[i + 1][k] - kViridis[i][k])));
  }
  return c;
}

}  // namespace

RgbImage colourDepth(const std::vector<float>& depth, int width, int height, double max_range) {
  if (width <= 0 || height <= 0 || depth.size() != static_cast<std::size_t>(width) * height) {
    throw std::invalid_argument("colourDepth: " + std::to_string(depth.size()) + " ranges for a " +
                                std::to_string(width) + " x " + std::to_string(height) + " image");
  }
  if (!(max_range > 0.0)) throw std::invalid_argument("colourDepth: max_range must be > 0");
  RgbImage image{width, height, std::vector<std::uint8_t>(depth.size() * 3, 0)};
  for (std::size_t i = 0; i < depth.size(); ++i) {
    const float r = depth[i];
    if (!std::isfinite(r) || r <= 0.0F) continue;  // nothing seen: black
    const auto c = viridis(1.0 - r / max_range);
    std::copy(c.begin(), c.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  return image;
}

}  // namespace uampc::evaluator
