// Fixed time grids (a snapshot every period, a sample per control period): the next grid point
// after a time, computed in one step. Stepping to it by repeated addition hangs on a time far ahead
// (a clock jump or a corrupt stamp: 2^31 s at a 1 ms period is 2e12 additions; the fuzzer found it).
#pragma once

#include <cmath>
#include <limits>

namespace uampc::evaluator {

// The first point grid_point + k * period (k >= 0) strictly after time; grid_point itself when it
// already is. period must be positive and finite. At magnitudes where period is below the
// resolution of a double, the next representable time after `time`.
inline double firstGridPointAfter(double grid_point, double time, double period) {
  if (grid_point > time || !std::isfinite(time)) return grid_point;
  const double next = grid_point + (std::floor((time - grid_point) / period) + 1.0) * period;
  return next > time ? next : std::nextafter(time, std::numeric_limits<double>::infinity());
}

}  // namespace uampc::evaluator
