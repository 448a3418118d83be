// TUM trajectory files: one pose per line, "t x y z qx qy qz qw", full precision.
#pragma once

#include <string>
#include <vector>

#include "uampc/evaluator/timed_pose.hpp"

namespace uampc::evaluator {

// Numbers are written shortest round-trip (reading gives back the same doubles). The quaternion
// is normalised with qw >= 0. Throws std::runtime_error naming path when it cannot write.
void writeTumTrajectory(const std::string& path, const std::vector<TimedPose>& poses);

// Blank lines and lines starting with '#' are skipped; throws std::runtime_error naming path and
// line on a malformed line or when the file cannot be opened.
std::vector<TimedPose> readTumTrajectory(const std::string& path);

}  // namespace uampc::evaluator
