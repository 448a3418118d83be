// How far from the origin a pose or map point read from a file may lie. Embree asserts (and the
// ray-caster aborts with signal 6) on a ray whose origin is near float's range; a pose at 1e20 m did
// that. Nothing a scene describes is 1000 km across, so files are refused well before that, by the
// readers, naming file and line (docs/user/faults.md, docs/decisions/coordinate-bound.md).
#pragma once

#include <Eigen/Core>
#include <string>

#include "uampc/world/short_number.hpp"

namespace uampc::world {

constexpr double kMaxDistanceFromOrigin = 1e6;  // m

// False for a finite point beyond the bound; non-finite points are the readers' other checks' job.
template <typename Vector>
bool withinCoordinateBound(const Vector& p) {
  return !p.allFinite() || p.template cast<double>().norm() <= kMaxDistanceFromOrigin;
}

// "is 1e+20 m from the origin, beyond the 1e+06 m a map or trajectory may reach"
template <typename Vector>
std::string beyondBoundText(const Vector& p) {
  return "is " + shortNumber(p.template cast<double>().norm()) + " m from the origin, beyond the " +
         shortNumber(kMaxDistanceFromOrigin) + " m a trajectory or map may reach";
}

}  // namespace uampc::world
