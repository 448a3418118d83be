// Turns a depth image (the controller's panorama, 32FC1 in metres, 0 = nothing seen) into colours
// a person can read: near is bright yellow, far is dark blue (viridis), empty pixels are black.
#pragma once

#include <vector>

#include "uampc/evaluator/png_image.hpp"

namespace uampc::evaluator {

// depth holds width * height ranges, row-major; ranges at or beyond max_range take the far colour.
// Non-finite or non-positive ranges are empty. Throws std::invalid_argument on a size mismatch or
// max_range <= 0.
RgbImage colourDepth(const std::vector<float>& depth, int width, int height, double max_range);

}  // namespace uampc::evaluator
