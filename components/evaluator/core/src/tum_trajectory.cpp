#include "uampc/evaluator/tum_trajectory.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uampc/run_files/number_format.hpp"
#include "uampc/run_files/text_file.hpp"

namespace uampc::evaluator {

void writeTumTrajectory(const std::string& path, const std::vector<TimedPose>& poses) {
  std::ostringstream out;
  out << "# t x y z qx qy qz qw\n";
  for (const TimedPose& p : poses) {
    Eigen::Quaterniond q(p.pose.rotation());
    q.normalize();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d& r = p.pose.translation();
    out << run_files::formatDouble(p.time) << ' ' << run_files::formatDouble(r.x()) << ' '
        << run_files::formatDouble(r.y()) << ' ' << run_files::formatDouble(r.z()) << ' '
        << run_files::formatDouble(q.x()) << ' ' << run_files::formatDouble(q.y()) << ' '
        << run_files::formatDouble(q.z()) << ' ' << run_files::formatDouble(q.w()) << '\n';
  }
  run_files::writeTextFile(path, out.str());  // whole or absent, the reason named on failure
}

std::vector<TimedPose> readTumTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open TUM trajectory file " + path);
  std::vector<TimedPose> poses;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto fail = [&](const std::string& why) {
      return std::runtime_error(path + ":" + std::to_string(number) + ": " + why);
    };
    std::istringstream fields(line);
    double v[8];
    std::string token;
    for (int i = 0; i < 8; ++i) {
      if (!(fields >> token)) throw fail("expected 8 numbers: t x y z qx qy qz qw");
      char* end = nullptr;
      v[i] = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size()) throw fail("not a number: '" + token + "'");
    }
    if (fields >> token) throw fail("more than 8 numbers");
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (!(q.norm() > 1e-9)) throw fail("quaternion of zero norm");
    TimedPose pose;
    pose.time = v[0];
    pose.pose.linear() = q.normalized().toRotationMatrix();
    pose.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace uampc::evaluator
