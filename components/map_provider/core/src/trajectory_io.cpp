#include "uampc/world/trajectory_io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "uampc/run_files/text_file.hpp"
#include "uampc/world/coordinate_bound.hpp"

namespace uampc::world {
namespace {

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
  throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

// Budgets checked while reading, before memory runs out: no pose line is near 4096 bytes, and ten
// million poses are 2.8 hours at 1 kHz. (/dev/zero, which has no line break, was read 2.1 GB deep.)
constexpr std::size_t kMaxLineBytes = 4096;
constexpr std::size_t kMaxPoses = 10'000'000;

// std::getline with a bound on the line's length; false at the end of the file.
bool readLine(std::istream& in, std::string& text, const std::string& path, std::size_t line) {
  text.clear();
  for (char c; in.get(c);) {
    if (c == '\n') return true;
    if (text.size() == kMaxLineBytes) {
      fail(path, line, "line longer than " + std::to_string(kMaxLineBytes) + " bytes: not a trajectory file?");
    }
    text.push_back(c);
  }
  return !text.empty();
}

void checkPoseBudget(const std::vector<TimedPose>& poses, const std::string& path, std::size_t line) {
  if (poses.size() >= kMaxPoses) fail(path, line, "more than " + std::to_string(kMaxPoses) + " poses");
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line, bool comma) {
  std::vector<std::string> fields;
  if (comma) {
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) fields.push_back(trim(field));
    if (!line.empty() && line.back() == ',') fields.emplace_back();
  } else {
    std::istringstream in(line);
    std::string field;
    while (in >> field) fields.push_back(field);
  }
  return fields;
}

double parseNumber(const std::string& text, const char* name, const std::string& path, std::size_t line) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) {
    fail(path, line, std::string("column ") + name + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(value) || errno == ERANGE) {
    fail(path, line, std::string("column ") + name + ": '" + text + "' is not finite");
  }
  return value;
}

// Fields t x y z qx qy qz qw starting at column first.
TimedPose parsePose(const std::vector<std::string>& f, std::size_t first, const std::string& path, std::size_t line) {
  static const char* kNames[] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};
  double v[8];
  for (int i = 0; i < 8; ++i) v[i] = parseNumber(f[first + i], kNames[i], path, line);
  TimedPose p;
  p.time = v[0];
  p.position = {v[1], v[2], v[3]};
  if (!withinCoordinateBound(p.position)) fail(path, line, "position " + beyondBoundText(p.position));
  p.orientation = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);  // w, x, y, z
  const double norm = p.orientation.norm();
  if (norm < 1e-6) fail(path, line, "quaternion has zero norm");
  p.orientation.coeffs() /= norm;
  return p;
}

void checkOrder(const std::vector<TimedPose>& poses, const TimedPose& next, const TrajectoryReadOptions& options,
                const std::string& path, std::size_t line) {
  if (poses.empty()) return;
  const double dt = next.time - poses.back().time;
  std::ostringstream msg;
  msg << std::setprecision(17);
  if (!(dt > 0.0)) {
    msg << "time " << next.time << " is not after the previous pose's " << poses.back().time;
    fail(path, line, msg.str());
  }
  if (options.max_gap > 0.0 && dt > options.max_gap) {
    msg << std::setprecision(6) << "gap of " << dt << " s to the previous pose exceeds max_gap " << options.max_gap
        << " s";
    fail(path, line, msg.str());
  }
}

Trajectory finish(std::vector<TimedPose> poses, const TrajectoryReadOptions& options, const std::string& path) {
  if (poses.empty()) throw std::runtime_error(path + ": no poses in file");
  applyAttitudeMode(poses, options.attitude, options.frame_correction);
  if (options.start_at_zero) {
    const double t0 = poses.front().time;
    for (auto& p : poses) p.time -= t0;
  }
  return Trajectory(std::move(poses));
}

std::ifstream openOrThrow(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open trajectory file");
  return in;
}

}  // namespace

TrajectoryReadOptions TrajectoryReadOptions::forMcd() {
  TrajectoryReadOptions o;
  o.attitude = AttitudeMode::kFromFile;
  o.frame_correction = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  return o;
}

Trajectory readMcdCsv(const std::string& path, const TrajectoryReadOptions& options) {
  std::ifstream in = openOrThrow(path);
  std::vector<TimedPose> poses;
  std::string text;
  std::size_t line = 0;
  bool header_seen = false;
  while (readLine(in, text, path, line + 1)) {
    ++line;
    const std::string trimmed = trim(text);
    if (trimmed.empty()) continue;
    const auto fields = split(trimmed, true);
    if (!header_seen) {
      std::string joined;
      for (const auto& f : fields) joined += (joined.empty() ? "" : ",") + f;
      if (joined != "num,t,x,y,z,qx,qy,qz,qw") {
        fail(path, line, "expected header 'num,t,x,y,z,qx,qy,qz,qw', got '" + trimmed + "'");
      }
      header_seen = true;
      continue;
    }
    if (fields.size() != 9) {
      fail(path, line, "expected 9 columns, got " + std::to_string(fields.size()));
    }
    parseNumber(fields[0], "num", path, line);
    TimedPose pose = parsePose(fields, 1, path, line);
    checkOrder(poses, pose, options, path, line);
    checkPoseBudget(poses, path, line);
    poses.push_back(pose);
  }
  if (!header_seen) throw std::runtime_error(path + ": empty trajectory file");
  return finish(std::move(poses), options, path);
}

Trajectory readTum(const std::string& path, const TrajectoryReadOptions& options) {
  std::ifstream in = openOrThrow(path);
  std::vector<TimedPose> poses;
  std::string text;
  std::size_t line = 0;
  while (readLine(in, text, path, line + 1)) {
    ++line;
    const std::string trimmed = trim(text);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const auto fields = split(trimmed, false);
    if (fields.size() != 8) {
      fail(path, line, "expected 8 columns, got " + std::to_string(fields.size()));
    }
    TimedPose pose = parsePose(fields, 0, path, line);
    checkOrder(poses, pose, options, path, line);
    checkPoseBudget(poses, path, line);
    poses.push_back(pose);
  }
  return finish(std::move(poses), options, path);
}

Trajectory readTrajectory(const std::string& path, const TrajectoryReadOptions& options) {
  const bool csv = path.size() >= 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
  return csv ? readMcdCsv(path, options) : readTum(path, options);
}

void writeTum(const std::string& path, const Trajectory& trajectory) {
  std::ostringstream out;
  out << "# t x y z qx qy qz qw\n" << std::setprecision(17);
  for (const auto& p : trajectory.poses()) {
    const auto& q = p.orientation;
    out << p.time << ' ' << p.position.x() << ' ' << p.position.y() << ' ' << p.position.z() << ' ' << q.x() << ' '
        << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
  run_files::writeTextFile(path, out.str());  // whole or absent
}

}  // namespace uampc::world
