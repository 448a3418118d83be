// calibration_matrix: each known mounting error cast into a still rig's recording (the simulator's
// core, the scenes' 2 cm range noise, the motor stepping between speeds) and calibrated by
// libs/calibration; one CSV row per world, seed and error with what was recovered, and a
// Markdown summary per error (docs/results/calibration.md).
//
//   build/bench/calibration_matrix --out calibration.csv [--seconds 30] [--seeds 3]
//                                  [--worlds campus,corridor,mcd_kth] [--cases NAME,...]
//                                  [--lo-seconds 60 [--lo-seeds 1]]
//
// With --lo-seconds, each case of the first --lo-seeds seeds also drives the LO along the world's
// path for that long three times (lo_effect.hpp): believing the true rig, the uncalibrated (believed)
// one, and the calibrated one, and reports their ATE.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "lo_effect.hpp"
#include "simulated_recording.hpp"
#include "uampc/calibration/rig_estimator.hpp"
#include "uampc/calibration/rig_model.hpp"

namespace uampc::calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Case {
  std::string name;
  frames::MountingError error;
};

// Rotations about a tilted axis (roll and pitch both, some yaw), offsets partly along the axis.
std::vector<Case> cases() {
  std::vector<Case> all;
  for (double a : {0.5, 1.0, 2.0, 5.0}) {
    Case c{"rotation " + std::to_string(a).substr(0, 3) + " deg", {}};
    c.error.rotation_rpy = Eigen::Vector3d(0.6, -0.8, 0.5) * a * kDeg;
    all.push_back(c);
  }
  for (double d : {0.01, 0.02, 0.05}) {
    Case c{"offset " + std::to_string(static_cast<int>(d * 100)) + " cm", {}};
    c.error.offset = Eigen::Vector3d(0.6, -0.8, 0.5) * d;
    all.push_back(c);
  }
  for (double e : {2.0, 5.0}) {
    Case c{"encoder zero " + std::to_string(static_cast<int>(e)) + " deg", {}};
    c.error.encoder_offset = e * kDeg;
    all.push_back(c);
  }
  for (double dt : {0.001, 0.005, 0.01, 0.02}) {
    Case c{"clock " + std::to_string(static_cast<int>(dt * 1000)) + " ms", {}};
    c.error.time_offset = dt;
    all.push_back(c);
  }
  Case all_of{"all: 2 deg, 2 cm, 3 deg, 10 ms", {}};
  all_of.error.rotation_rpy = Eigen::Vector3d(0.6, -0.8, 0.5) * 2.0 * kDeg;
  all_of.error.offset = Eigen::Vector3d(0.6, -0.8, 0.5) * 0.02;
  all_of.error.encoder_offset = 3.0 * kDeg;
  all_of.error.time_offset = 0.01;
  all.push_back(all_of);
  return all;
}

// The MCD trajectory file of an MCD world, empty for a procedural one.
std::string trajectoryFileOf(const std::string& world) {
  const std::map<std::string, std::string> mcd = {
      {"mcd_kth", "kth_day06.csv"}, {"mcd_ntu", "ntu_day01.csv"}, {"mcd_tuhh", "tuhh_day03.csv"}};
  const auto it = mcd.find(world);
  return it == mcd.end() ? std::string() : UAMPC_SOURCE_DIR "/data/mcd/" + it->second;
}

// The motor axis in the LiDAR frame: what roll and pitch determine.
Eigen::Vector3d motorAxisInLidar(double roll, double pitch) {
  return frames::rotationFromRollPitchYaw({roll, pitch, 0.0}).transpose() * Eigen::Vector3d::UnitZ();
}

struct Errors {
  double axis_deg, offset_m, time_s, axis_sd_deg, offset_sd_m, time_sd_s, seconds;
  bool time_estimated;
};

// The LO's ATE believing the true, the uncalibrated and the calibrated rig.
struct LoEffect {
  LoDriveResult known, uncalibrated, calibrated;
};

LoEffect loEffect(const std::string& world, std::uint64_t seed, double seconds,
                  const frames::MotorLidarCalibration& truth, const frames::MotorLidarCalibration& believed,
                  const frames::MotorLidarCalibration& calibrated) {
  LoDrive drive;
  drive.source = trajectoryFileOf(world).empty() ? world : trajectoryFileOf(world);
  drive.seed = seed;
  drive.seconds = seconds;
  return {driveLo(drive, truth, truth), driveLo(drive, truth, believed), driveLo(drive, truth, calibrated)};
}

std::string ateCells(const LoDriveResult& r) {
  return std::to_string(r.ate.aligned) + "," + std::to_string(r.ate.unaligned) + "," +
         (r.runaway_at ? std::to_string(*r.runaway_at) : std::string());
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Errors recoveryErrors(const CalibrationResult& r, const ObservableRig& want) {
  auto estimate = [&](const std::string& name) -> const ParameterEstimate& {
    for (const auto& p : r.parameters)
      if (p.name == name) return p;
    throw std::logic_error(name);
  };
  const double roll = estimate("roll_deg").value * kDeg, pitch = estimate("pitch_deg").value * kDeg;
  const double angle = std::acos(
      std::clamp(motorAxisInLidar(roll, pitch).dot(motorAxisInLidar(want.rotation[0], want.rotation[1])), -1.0, 1.0));
  Errors e{};
  e.axis_deg = angle / kDeg;
  e.offset_m = std::hypot(estimate("x").value - want.offset[0], estimate("y").value - want.offset[1]);
  e.time_s = std::abs(estimate("time_offset").value - want.time_offset[0]);
  e.time_estimated = estimate("time_offset").estimated;
  e.axis_sd_deg = std::hypot(estimate("roll_deg").stddev, estimate("pitch_deg").stddev);
  e.offset_sd_m = std::hypot(estimate("x").stddev, estimate("y").stddev);
  e.time_sd_s = estimate("time_offset").stddev;
  return e;
}

test::SimulatedRig rigIn(const std::string& world, double seconds, std::uint64_t seed) {
  test::SimulatedRig rig;
  rig.world = world;
  rig.trajectory_file = trajectoryFileOf(world);
  rig.seconds = seconds;
  rig.seed = seed;
  return rig;
}

}  // namespace
}  // namespace uampc::calibration

int main(int argc, char** argv) {
  using namespace uampc::calibration;
  CLI::App app{"Known mounting errors against what the rig calibration recovers (docs/results/calibration.md)"};
  std::string out, world_list = "campus,corridor,mcd_kth", case_list;
  double seconds = 30.0;
  int seeds = 3;
  app.add_option("--out", out, "CSV file, one row per world, seed and error")->required();
  app.add_option("--seconds", seconds, "recording length, s")->check(CLI::Range(1.0, 600.0));
  app.add_option("--seeds", seeds, "seeds per world and error")->check(CLI::Range(1, 100));
  app.add_option("--worlds", world_list, "comma-separated: campus, corridor, multilevel, mcd_kth, mcd_ntu, mcd_tuhh");
  app.add_option("--cases", case_list, "comma-separated case names (default: all)");
  double lo_seconds = 0.0;
  int lo_seeds = 1;
  app.add_option("--lo-seconds", lo_seconds,
                 "also drive the LO this long along the world's path believing the true, uncalibrated and calibrated "
                 "rig (0: not)")
      ->check(CLI::Range(0.0, 3600.0));
  app.add_option("--lo-seeds", lo_seeds, "the LO drives for the first N seeds only")->check(CLI::Range(1, 100));
  CLI11_PARSE(app, argc, argv);

  std::vector<std::string> worlds;
  for (std::size_t from = 0, comma; from <= world_list.size(); from = comma + 1) {
    comma = world_list.find(',', from);
    if (comma == std::string::npos) comma = world_list.size();
    worlds.push_back(world_list.substr(from, comma - from));
  }
  std::ofstream csv(out);
  csv << "world,seed,case,axis_error_deg,axis_sd_deg,offset_error_m,offset_sd_m,time_error_s,time_sd_s,"
         "time_estimated,terms,median_before_m,median_after_m,seconds,"
         "lo_known_ate_aligned_m,lo_known_ate_m,lo_known_runaway_s,lo_uncalibrated_ate_aligned_m,lo_uncalibrated_ate_m,"
         "lo_uncalibrated_runaway_s,lo_calibrated_ate_aligned_m,lo_calibrated_ate_m,lo_calibrated_runaway_s\n";
  const auto believed = uampc::frames::MotorLidarCalibration::referenceRig();
  std::map<std::string, std::vector<Errors>> by_case;
  std::map<std::string, std::vector<LoEffect>> lo_by_case;
  for (const auto& c : cases()) {
    if (!case_list.empty() && case_list.find(c.name) == std::string::npos) continue;
    for (const auto& world : worlds) {
      for (int seed = 1; seed <= seeds; ++seed) {
        test::SimulatedRig rig = rigIn(world, seconds, static_cast<std::uint64_t>(seed));
        rig.truth = uampc::frames::withMountingError(believed, c.error);
        const RigRecording recording = test::simulatedRecording(rig);
        const auto start = std::chrono::steady_clock::now();
        Errors e{};
        std::string note;
        try {
          const CalibrationResult r = estimateRig(recording, believed);
          e = recoveryErrors(r, truthInGaugeOf(rig.truth, believed));
          e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          csv << world << "," << seed << ",\"" << c.name << "\"," << e.axis_deg << "," << e.axis_sd_deg << "," << e.offset_m
              << "," << e.offset_sd_m << "," << e.time_s << "," << e.time_sd_s << "," << e.time_estimated << ","
              << r.terms << "," << r.median_distance_before << "," << r.median_distance_after << "," << e.seconds;
          by_case[c.name].push_back(e);
          if (lo_seconds > 0.0 && seed <= lo_seeds) {
            const LoEffect lo = loEffect(world, static_cast<std::uint64_t>(seed), lo_seconds, rig.truth, believed,
                                         r.calibration);
            csv << "," << ateCells(lo.known) << "," << ateCells(lo.uncalibrated) << "," << ateCells(lo.calibrated);
            lo_by_case[c.name].push_back(lo);
            std::fprintf(stderr, "  LO ATE aligned: true rig %.3f m, uncalibrated %.3f m, calibrated %.3f m\n",
                         lo.known.ate.aligned, lo.uncalibrated.ate.aligned, lo.calibrated.ate.aligned);
          } else {
            csv << ",,,,,,,,,";
          }
          csv << "\n";
        } catch (const CalibrationError& error) {
          csv << world << "," << seed << ",\"" << c.name << "\",,,,,,,,,,,,,,,,,,,,\n";
          note = std::string(" refused: ") + error.what();
        }
        csv.flush();
        std::fprintf(stderr, "%s, %s, seed %d: axis %.4f deg, offset %.2f mm, clock %.3f ms (%.1f s)%s\n",
                     c.name.c_str(), world.c_str(), seed, e.axis_deg, e.offset_m * 1e3, e.time_s * 1e3, e.seconds,
                     note.c_str());
      }
    }
  }
  std::printf(
      "| error | runs | axis error, max (deg) | axis sd, mean (deg) | offset error, max (mm) | offset sd, "
      "mean (mm) | clock error, max (ms) | clock sd, mean (ms) | time, max (s) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& c : cases()) {
    const auto it = by_case.find(c.name);
    if (it == by_case.end()) continue;
    Errors worst{}, mean{};
    for (const auto& e : it->second) {
      worst.axis_deg = std::max(worst.axis_deg, e.axis_deg);
      worst.offset_m = std::max(worst.offset_m, e.offset_m);
      worst.time_s = std::max(worst.time_s, e.time_s);
      worst.seconds = std::max(worst.seconds, e.seconds);
      mean.axis_sd_deg += e.axis_sd_deg / static_cast<double>(it->second.size());
      mean.offset_sd_m += e.offset_sd_m / static_cast<double>(it->second.size());
      mean.time_sd_s += e.time_sd_s / static_cast<double>(it->second.size());
    }
    std::printf("| %s | %zu | %.4f | %.4f | %.2f | %.2f | %.3f | %.3f | %.1f |\n", c.name.c_str(), it->second.size(),
                worst.axis_deg, mean.axis_sd_deg, worst.offset_m * 1e3, mean.offset_sd_m * 1e3, worst.time_s * 1e3,
                mean.time_sd_s * 1e3, worst.seconds);
  }
  if (lo_by_case.empty()) return 0;
  std::printf(
      "\n| error | runs | LO ATE aligned, true rig, median (m) | uncalibrated / true, median | calibrated / true, "
      "median [range] | runaways: true, uncalibrated, calibrated |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const auto& c : cases()) {
    const auto it = lo_by_case.find(c.name);
    if (it == lo_by_case.end()) continue;
    std::vector<double> known, uncalibrated, calibrated;
    int runaways[3] = {0, 0, 0};
    for (const LoEffect& lo : it->second) {
      known.push_back(lo.known.ate.aligned);
      uncalibrated.push_back(lo.uncalibrated.ate.aligned / lo.known.ate.aligned);
      calibrated.push_back(lo.calibrated.ate.aligned / lo.known.ate.aligned);
      runaways[0] += lo.known.runaway_at.has_value();
      runaways[1] += lo.uncalibrated.runaway_at.has_value();
      runaways[2] += lo.calibrated.runaway_at.has_value();
    }
    std::printf("| %s | %zu | %.3f | %.2f | %.3f [%.3f-%.3f] | %d, %d, %d |\n", c.name.c_str(), it->second.size(),
                median(known), median(uncalibrated), median(calibrated),
                *std::min_element(calibrated.begin(), calibrated.end()),
                *std::max_element(calibrated.begin(), calibrated.end()), runaways[0], runaways[1], runaways[2]);
  }
  return 0;
}
