#include "uampc/evaluator/depth_colouring.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "uampc/colour_map/viridis.hpp"

namespace uampc::evaluator {

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
    const auto c = colour_map::viridis(1.0 - r / max_range);
    std::copy(c.begin(), c.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  return image;
}

}  // namespace uampc::evaluator
