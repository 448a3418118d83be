// evaluator: measures a run as the paper does (docs/dev/architecture.md section 1, "Evaluation").
//   ATE: the LO's poses against ground truth interpolated at their exact stamps, unaligned (the
//        paper's figure) and after SE(3) Umeyama alignment; RPE over 10 m and 100 m.
//   CMPLT: distinct 0.5 m voxels hit by the LO's registered scans per 5 s window, and the same from
//        the raw scans placed with ground truth (Eq. 1), so completeness is not confounded with drift.
// Publishes running figures; writes the run directory's files (--out; names and contents in
// libs/run_files): during the run motor.csv, timings.csv, uncertainty.csv and snapshots of the
// controller's panorama; at the end the trajectories, ate.csv, the CMPLT windows, scanned_voxels.bt
// (OctoMap, opens in octovis) and metrics.json last, with what the run was (run_info.json, written
// by `uampc launch` when the run started) as its "run" object.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "path_trail.hpp"
#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/evaluator/completeness.hpp"
#include "uampc/evaluator/depth_colouring.hpp"
#include "uampc/evaluator/motor_activity.hpp"
#include "uampc/evaluator/periodic_grid.hpp"
#include "uampc/evaluator/pose_interpolator.hpp"
#include "uampc/evaluator/report_files.hpp"
#include "uampc/evaluator/trajectory_evaluator.hpp"
#include "uampc/evaluator/tum_trajectory.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/frames/pose_knots.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_info.hpp"
#include "uampc/run_files/time_series.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

class EvaluatorComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "ATE, RPE and CMPLT of a run; writes metrics, trajectories and time series";
    spec.input<nav_msgs::msg::Odometry>("odometry", "/lo/odometry", QosPreset::kControl, "estimated base poses");
    spec.input<geometry_msgs::msg::PoseStamped>("ground_truth", "/ground_truth/pose", QosPreset::kControl,
                                                "ground-truth base poses");
    spec.input<sensor_msgs::msg::PointCloud2>("registered", "/lo/registered", QosPreset::kSensor,
                                              "registered scans, world frame (CMPLT)");
    spec.input<sensor_msgs::msg::PointCloud2>("scan", "/lidar/points", QosPreset::kSensor,
                                              "raw scans, placed with ground truth (ground-truth CMPLT)");
    spec.input<sensor_msgs::msg::JointState>("motor_state", "/motor/state", QosPreset::kControl, "encoder states");
    spec.input<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "motor commands");
    spec.input<msg::UncertaintyProfile>("profile", "/mpc/uncertainty", QosPreset::kSensor, "controller's U profile");
    spec.input<msg::Metrics>("lo_metrics", "/lo/metrics", QosPreset::kSensor, "LO timings and degeneracy");
    spec.input<msg::Metrics>("mpc_timing", "/mpc/timing", QosPreset::kSensor, "controller timings");
    spec.input<sensor_msgs::msg::Image>("panorama", "/mpc/panorama", QosPreset::kSensor,
                                        "controller's panoramic depth map (32FC1), saved as snapshots");
    spec.output<msg::Metrics>("metrics", "/evaluator/metrics", QosPreset::kSensor, "running ATE and CMPLT")
        .forViewers();
    spec.output<nav_msgs::msg::Path>("estimated_path", "/evaluator/estimated_path", QosPreset::kSensor,
                                     "the LO's trajectory so far, for viewers")
        .forViewers();
    spec.output<nav_msgs::msg::Path>("true_path", "/evaluator/true_path", QosPreset::kSensor,
                                     "the ground-truth trajectory so far, for viewers")
        .forViewers();
    evaluator::CompletenessConfig defaults;
    ParameterBinding binding(spec);
    bindCompletenessParameters(binding, defaults);
    // Not bound: the core keeps grid_offset 0 (its tests place points on the unshifted grid's
    // faces). Not 0 here: procedural indoor worlds put walls on round coordinates, i.e. on voxel
    // faces, where exactly posed points fall on both sides and count twice (see completeness.hpp).
    spec.param("grid_offset", 0.1234,
               "CMPLT voxel grid shifted by this on every axis, m, so that walls at round coordinates do not lie "
               "on voxel faces (the saved .bt holds the shifted grid's voxels)")
        .between(-100.0, 100.0);
    adapters::declareRigParameters(spec);  // to place raw scans with ground truth
    spec.param("report_period", 5.0, "running figures are published every this many s").between(0.1, 3600.0);
    spec.param("path_period", 0.5, "the paths for viewers are published every this many s of sim time")
        .between(0.05, 3600.0);
    spec.param("path_spacing", 0.1,
               "the paths for viewers keep at most one pose per this many s (doubled whenever a path reaches "
               "2000 poses)")
        .between(0.0, 60.0);
    spec.param("panorama_period", 20.0, "a panorama snapshot (PNG) every this many s of sim time; 0: none")
        .between(0.0, 1e6);
    spec.param("panorama_max_range", 40.0, "range shown darkest in the snapshots, m (the Mid-360's: 40)")
        .between(0.1, 1e4);
  }

  explicit EvaluatorComponent(Context& ctx)
      : ctx_(ctx),
        trajectory_([this](double t) { return ground_truth_(t); }),
        cmplt_(completenessFrom(ctx)),
        cmplt_gt_(completenessFrom(ctx)),
        metrics_pub_(ctx.publisher<msg::Metrics>("metrics")),
        estimated_path_pub_(ctx.publisher<nav_msgs::msg::Path>("estimated_path")),
        true_path_pub_(ctx.publisher<nav_msgs::msg::Path>("true_path")),
        estimated_trail_(ctx.paramDouble("path_spacing")),
        true_trail_(ctx.paramDouble("path_spacing")) {
    calibration_ = adapters::rigCalibration(ctx);
    const std::string& out = ctx.outputDirectory();
    if (out.empty()) {
      ctx.log().info("no output directory (uampc launch --out DIR): figures are logged but no files written");
    } else {
      std::filesystem::create_directories(out);
      motor_csv_ = std::make_unique<run_files::RowWriter<run_files::MotorRow>>(
          run_files::inDirectory(out, run_files::kMotorFile));
      timings_ = std::make_unique<run_files::TimingsWriter>(run_files::inDirectory(out, run_files::kTimingsFile));
      uncertainty_ =
          std::make_unique<run_files::UncertaintyWriter>(run_files::inDirectory(out, run_files::kUncertaintyFile));
      run_info_ = readRunInfo(out);
    }
    ctx.subscribe<geometry_msgs::msg::PoseStamped>("ground_truth", [this](const geometry_msgs::msg::PoseStamped& m) {
      ground_truth_.add({fromMsg(m.header().stamp()).seconds(), adapters::toIsometry(m.pose())});
      true_trail_.add(m.header(), m.pose());
      flush();
    });
    ctx.subscribe<nav_msgs::msg::Odometry>("odometry", [this](const nav_msgs::msg::Odometry& m) {
      pending_estimates_.push_back({fromMsg(m.header().stamp()).seconds(), adapters::toIsometry(m.pose().pose())});
      estimated_trail_.add(m.header(), m.pose().pose());
      flush();
    });
    ctx.subscribe<sensor_msgs::msg::PointCloud2>("registered", [this](const sensor_msgs::msg::PointCloud2& m) {
      cmplt_.addScan(fromMsg(m.header().stamp()).seconds(), pointcloud::readCloud(m).positions);
    });
    ctx.subscribe<sensor_msgs::msg::PointCloud2>("scan", [this](const sensor_msgs::msg::PointCloud2& m) {
      const auto time_field = pointcloud::findTimeField(m);
      PendingScan scan{fromMsg(m.header().stamp()).seconds(), pointcloud::readCloud(m, &time_field), 0.0, 0.0};
      // The frame's span, once: the scan may wait for ground truth through many flushes. A point
      // time that is not finite (a misbehaving driver) is left out of it: an infinite one would
      // hold the scan, and every scan behind it, back for good. Such points are not placed.
      scan.start = scan.end = scan.stamp;
      std::size_t non_finite = 0;
      for (float t : scan.points.time_offsets) {
        if (!std::isfinite(t)) {
          ++non_finite;
          continue;
        }
        scan.start = std::min(scan.start, scan.stamp + t);
        scan.end = std::max(scan.end, scan.stamp + t);
      }
      if (non_finite > 0) {
        non_finite_times_log_.warn(ctx_.log(), "scans on ", ctx_.topicOf("scan"),
                                   " have points with non-finite times (", non_finite,
                                   " in this one); they are not placed with ground truth (said once)");
      }
      pending_scans_.push_back(std::move(scan));
      flush();
    });
    ctx.subscribe<sensor_msgs::msg::JointState>("motor_state", [this](const sensor_msgs::msg::JointState& m) {
      if (m.position().empty()) return;
      const double t = fromMsg(m.header().stamp()).seconds();
      const double omega = m.velocity().empty() ? 0.0 : m.velocity()[0];
      motor_.add(frames::rotorReading({t, m.position()[0], omega}, calibration_));  // Eq. 1's theta(t)
      motor_activity_.add(t, omega, command_);
      if (motor_csv_) writeOutput([&] { motor_csv_->add({t, m.position()[0], omega, command_}); });
      flush();
    });
    ctx.subscribe<msg::MotorCommand>("command", [this](const msg::MotorCommand& m) { command_ = m.velocity(); });
    ctx.subscribe<msg::UncertaintyProfile>("profile", [this](const msg::UncertaintyProfile& m) {
      if (!uncertainty_ || m.samples().empty()) return;
      try {
        writeOutput([&] {
          uncertainty_->add({fromMsg(m.header().stamp()).seconds(), m.theta_start(), m.delta_theta(), m.command(),
                             std::vector<double>(m.samples().begin(), m.samples().end())});
        });
      } catch (const std::invalid_argument& e) {
        // A controller that changed its sample count: the file's columns cannot hold the row.
        bad_profile_log_.warn(ctx_.log(), "profiles on ", ctx_.topicOf("profile"), ": ", e.what(), " (said once)");
      }
    });
    auto onMetrics = [this](const msg::Metrics& m) {
      if (!timings_) return;
      writeOutput([&] {
        for (const auto& v : m.values())
          timings_->add({fromMsg(m.header().stamp()).seconds(), m.source(), v.name(), v.value()});
      });
    };
    ctx.subscribe<msg::Metrics>("lo_metrics", [this, onMetrics](const msg::Metrics& m) {
      onMetrics(m);
      onLoStatus(m);
    });
    ctx.subscribe<msg::Metrics>("mpc_timing", onMetrics);
    panorama_period_ = ctx.paramDouble("panorama_period");
    panorama_max_range_ = ctx.paramDouble("panorama_max_range");
    next_panorama_ = panorama_period_;
    const bool save_panoramas = !out.empty() && panorama_period_ > 0.0;
    // Subscribed even when no snapshot is wanted: every declared port must be opened.
    ctx.subscribe<sensor_msgs::msg::Image>("panorama", [this, save_panoramas](const sensor_msgs::msg::Image& m) {
      if (save_panoramas) writeOutput([&] { onPanorama(m); });
    });
    ctx.timer(ctx.paramDouble("report_period"), [this] { publishRunning(); });
    ctx.timer(ctx.paramDouble("path_period"), [this] { publishPaths(); });
  }

  void shutdown() override {
    flush();
    const auto trajectory = trajectory_.report();
    const auto cmplt = cmplt_.report(ctx_.now().seconds());
    const auto cmplt_gt = cmplt_gt_.report(ctx_.now().seconds());
    ctx_.log().info("ATE ", trajectory.ate.unaligned.rmse, " m (aligned ", trajectory.ate.aligned.rmse, " m) over ",
                    trajectory.paired, " poses; CMPLT ", cmplt.mean_voxels_per_window, " voxels per window (",
                    cmplt_gt.mean_voxels_per_window, " with ground truth)");
    const std::string& out = ctx_.outputDirectory();
    if (out.empty()) return;
    if (!output_failure_.empty()) {
      // The run already failed with the file named; a metrics.json would pass it for complete.
      ctx_.log().warn("no ", run_files::kMetricsFile, " for this run: its outputs are incomplete (", output_failure_,
                      ")");
      return;
    }
    closeTimeSeries();
    writeEndOfRunFiles(out, trajectory, cmplt, cmplt_gt);
    // Last, and only when everything before it was written whole: a run directory with a
    // metrics.json holds the run's complete outputs (docs/decisions/run-files-whole-or-absent.md).
    run_files::writeMetricsFile(run_files::inDirectory(out, run_files::kMetricsFile),
                                metricsDocument(trajectory, cmplt, cmplt_gt));
  }

 private:
  // Runs a write of the run directory's files. A failure is kept, so that shutdown writes no
  // metrics.json for a run whose outputs were cut, and thrown on: the runtime stops the run with
  // the component and the file named (docs/user/faults.md).
  template <class Write>
  void writeOutput(Write&& write) {
    try {
      write();
    } catch (const std::runtime_error& e) {
      if (output_failure_.empty()) output_failure_ = e.what();
      throw;
    }
  }

  // The files written through the run, flushed and closed: their last rows may fail only here.
  void closeTimeSeries() {
    if (motor_csv_) motor_csv_->close();
    if (timings_) timings_->close();
    if (uncertainty_) uncertainty_->close();
  }

  void writeEndOfRunFiles(const std::string& out, const evaluator::TrajectoryReport& trajectory,
                          const evaluator::CompletenessReport& cmplt, const evaluator::CompletenessReport& cmplt_gt) {
    using run_files::inDirectory;
    evaluator::writeTumTrajectory(inDirectory(out, run_files::kEstimateFile), trajectory_.pairedEstimates());
    evaluator::writeTumTrajectory(inDirectory(out, run_files::kGroundTruthFile), trajectory_.pairedGroundTruth());
    evaluator::writeAteSeriesCsv(inDirectory(out, run_files::kAteFile), trajectory.ate.series);
    evaluator::writeCompletenessWindowsCsv(inDirectory(out, run_files::kCompletenessWindowsFile), cmplt.windows);
    evaluator::writeCompletenessWindowsCsv(inDirectory(out, run_files::kGroundTruthCompletenessWindowsFile),
                                           cmplt_gt.windows);
    cmplt_gt_.saveOctree(inDirectory(out, run_files::kScannedVoxelsFile));
  }

  run_files::MetricsDocument metricsDocument(const evaluator::TrajectoryReport& trajectory,
                                             const evaluator::CompletenessReport& cmplt,
                                             const evaluator::CompletenessReport& cmplt_gt) const {
    run_files::MetricsDocument metrics;
    metrics.sim_time = ctx_.now().seconds();
    metrics.trajectory = evaluator::toSummary(trajectory);
    metrics.cmplt = evaluator::toSummary(cmplt);
    metrics.cmplt_ground_truth = evaluator::toSummary(cmplt_gt);
    const evaluator::MotorActivityReport activity = motor_activity_.report();
    // Changes over one 0.1 s control period: how much the command chatters, and how much of it
    // the motor follows after the bridge's limits.
    metrics.motor = {activity.mean_speed, activity.speed_std, activity.command_change_rms, activity.speed_change_rms};
    // The LO's own account of its losses of track (its "lost" flag on /lo/metrics).
    if (first_lost_time_ >= 0.0) metrics.lo.first_lost_time = first_lost_time_;
    metrics.lo.lost_frames = lost_frames_;
    metrics.lo.rejected_updates = rejected_updates_;
    metrics.lo.velocity_resets = velocity_resets_;
    metrics.lo.frames = lo_frames_;
    metrics.lo.degenerate_frames = degenerate_frames_;
    metrics.run = run_info_;
    markWhetherTheRunReachedItsEnd(metrics);
    return metrics;
  }

  // A run cut short (a stop signal, a failed process) must not read as a whole one: its metrics
  // say whether the clock reached the scene's duration (docs/user/experiments.md). Within a step:
  // the last step's samples are the last the evaluator sees.
  void markWhetherTheRunReachedItsEnd(run_files::MetricsDocument& metrics) const {
    if (!run_info_ || run_info_->duration_s <= 0.0) return;
    metrics.scene_duration = run_info_->duration_s;
    metrics.reached_end = run_files::reachesEnd(metrics.sim_time, run_info_->duration_s, ctx_.step().seconds());
  }

  // The parameters that set CMPLT's config: declared from the core's defaults, read into them.
  static void bindCompletenessParameters(ParameterBinding& b, evaluator::CompletenessConfig& c) {
    b.bind("voxel_size", c.voxel_size, "CMPLT voxel size, m (the paper: 0.5)").between(0.01, 100.0);
    b.bind("window", c.window_duration, "CMPLT window, s (the paper: 5)").between(0.1, 3600.0);
  }

  // What the run was, from the launcher (one source: run_info.json, written from the resolved
  // scene); none when the process was started otherwise, e.g. `uampc run-process` by hand.
  std::optional<run_files::RunInfo> readRunInfo(const std::string& out) const {
    const std::string path = run_files::inDirectory(out, run_files::kRunInfoFile);
    if (!pathExists(path)) {
      ctx_.log().info("no ", path, " (the run was not started by uampc launch --out): metrics.json will not say ",
                      "what the run was");
      return std::nullopt;
    }
    try {
      return run_files::readRunInfoFile(path);
    } catch (const std::runtime_error& e) {
      ctx_.log().warn(e.what(), "; metrics.json will not say what the run was");
      return std::nullopt;
    }
  }

  static evaluator::CompletenessConfig completenessFrom(const Context& ctx) {
    evaluator::CompletenessConfig c;
    ParameterBinding binding(ctx);
    bindCompletenessParameters(binding, c);
    c.grid_offset = ctx.paramDouble("grid_offset");
    return c;
  }

  void onLoStatus(const msg::Metrics& m) {
    ++lo_frames_;
    for (const auto& v : m.values()) {
      if (v.name() == "lost" && v.value() > 0.5) {
        if (first_lost_time_ < 0.0) first_lost_time_ = fromMsg(m.header().stamp()).seconds();
        ++lost_frames_;
      } else if (v.name() == "rejected_updates") {
        rejected_updates_ = static_cast<long>(v.value());
      } else if (v.name() == "velocity_resets") {
        velocity_resets_ = static_cast<long>(v.value());
      } else if (v.name() == "degenerate_directions" && v.value() > 0.5) {
        ++degenerate_frames_;
      }
    }
  }

  struct PendingScan {
    double stamp;
    pointcloud::ScanPoints points;
    double start, end;  // s, its earliest and latest finite point times
  };

  // Saves one panorama per panorama_period as a PNG; a malformed image is reported once and skipped.
  void onPanorama(const sensor_msgs::msg::Image& m) {
    const double t = fromMsg(m.header().stamp()).seconds();
    if (t < next_panorama_) return;
    const std::size_t pixels = static_cast<std::size_t>(m.width()) * m.height();
    if (m.encoding() != "32FC1" || m.is_bigendian() != 0 || pixels == 0 || m.step() != m.width() * 4 ||
        m.data().size() != pixels * 4) {
      bad_panorama_log_.warn(ctx_.log(), "ignoring panoramas on ", ctx_.topicOf("panorama"),
                             ": expected little-endian 32FC1 with step = 4 * width and 4 * width * height bytes, got ",
                             m.encoding(), " ", m.width(), " x ", m.height(), ", step ", m.step(), ", ",
                             m.data().size(), " bytes");
      return;
    }
    std::vector<float> depth(pixels);
    std::memcpy(depth.data(), m.data().data(), pixels * 4);
    const std::string directory = run_files::inDirectory(ctx_.outputDirectory(), run_files::kPanoramaDirectory);
    std::filesystem::create_directories(directory);
    evaluator::writePng(
        run_files::inDirectory(directory, run_files::panoramaSnapshotName(t)),
        evaluator::colourDepth(depth, static_cast<int>(m.width()), static_cast<int>(m.height()), panorama_max_range_));
    next_panorama_ = evaluator::firstGridPointAfter(next_panorama_, t, panorama_period_);
  }

  // Ground truth streams in at the encoder rate; only the poses that pending estimates and scans
  // may still ask for are kept (the files hold the paired poses), so that a long run's memory stays
  // flat. kGroundTruthKept: a margin for estimates that arrive late; the LO's lag is one frame.
  static constexpr double kGroundTruthKept = 10.0;  // s
  void forgetOldGroundTruth() {
    double needed = ground_truth_.endTime();
    if (!pending_estimates_.empty()) needed = std::min(needed, pending_estimates_.front().time);
    if (!pending_scans_.empty()) needed = std::min(needed, pending_scans_.front().start);
    ground_truth_.dropBefore(needed - kGroundTruthKept);
  }

  // Pairs estimates and places raw scans once ground truth (and encoder states) cover them.
  void flush() {
    if (ground_truth_.empty()) return;
    forgetOldGroundTruth();
    const double covered = ground_truth_.endTime();
    while (!pending_estimates_.empty() && pending_estimates_.front().time <= covered) {
      trajectory_.addEstimate(pending_estimates_.front().time, pending_estimates_.front().pose);
      pending_estimates_.pop_front();
    }
    while (!pending_scans_.empty()) {
      const PendingScan& scan = pending_scans_.front();
      const double start = scan.start, end = scan.end;
      if (end > covered || motor_.empty() || motor_.newest().time < end) return;
      std::vector<Eigen::Vector3f> world;
      world.reserve(scan.points.positions.size());
      // Points from before the first ground-truth pose or encoder reading cannot be placed (the
      // first scan of a run); the rest get Eq. 1 with T_WL = T_WB * T_BL(theta) at their own
      // time, from knots (pose_knots.hpp).
      const double placeable = std::max({start, ground_truth_.startTime(), motor_.oldest().time});
      if (placeable <= end) {
        lidar_pose_.build(placeable, end, [&](double t) {
          return *ground_truth_(t) * frames::lidarPoseInBase(*motor_.thetaAt(t), calibration_);
        });
        for (std::size_t i = 0; i < scan.points.positions.size(); ++i) {
          const double t = scan.stamp + scan.points.time_offsets[i];
          if (!(t >= placeable && t <= end)) continue;  // not placeable yet, or not a finite time
          world.push_back((lidar_pose_(t) * scan.points.positions[i].cast<double>()).cast<float>());
        }
      }
      cmplt_gt_.addScan(scan.stamp, world);
      pending_scans_.pop_front();
    }
  }

  void publishRunning() {
    // Not trajectory_.report(): that copies and sorts every pair of the run, each report_period
    // (docs/results/soak.md).
    const evaluator::AteRmse ate = trajectory_.ateRmse();
    msg::Metrics m;
    m.header().stamp(toMsg(ctx_.now()));
    m.source(ctx_.name());
    auto add = [&](const char* name, double value, const char* unit) {
      msg::MetricValue v;
      v.name(name);
      v.value(value);
      v.unit(unit);
      m.values().push_back(v);
    };
    add("ate", ate.unaligned, "m");
    add("ate_aligned", ate.aligned, "m");
    add("cmplt", cmplt_.report().mean_voxels_per_window, "");
    add("cmplt_ground_truth", cmplt_gt_.report().mean_voxels_per_window, "");
    metrics_pub_.publish(m);
  }

  void publishPaths() {
    if (!estimated_trail_.empty()) estimated_path_pub_.publish(estimated_trail_.path());
    if (!true_trail_.empty()) true_path_pub_.publish(true_trail_.path());
  }

  Context& ctx_;
  frames::MotorLidarCalibration calibration_;
  frames::PoseKnots lidar_pose_;  // T_WL over the raw scan being placed
  RateLimitedLog non_finite_times_log_ = RateLimitedLog::once();
  evaluator::PoseInterpolator ground_truth_;
  evaluator::TrajectoryEvaluator trajectory_;
  evaluator::Completeness cmplt_;
  evaluator::Completeness cmplt_gt_;
  frames::MotorAngleTrack motor_{5.0};
  Publisher<msg::Metrics> metrics_pub_;
  Publisher<nav_msgs::msg::Path> estimated_path_pub_;
  Publisher<nav_msgs::msg::Path> true_path_pub_;
  PathTrail estimated_trail_;
  PathTrail true_trail_;
  std::deque<evaluator::TimedPose> pending_estimates_;
  std::deque<PendingScan> pending_scans_;
  std::unique_ptr<run_files::RowWriter<run_files::MotorRow>> motor_csv_;
  std::unique_ptr<run_files::TimingsWriter> timings_;
  double first_lost_time_ = -1.0;  // s; negative: the LO never said it was lost
  long lost_frames_ = 0;
  long lo_frames_ = 0;          // /lo/metrics messages
  long degenerate_frames_ = 0;  // of them, with a degenerate pose direction
  long rejected_updates_ = 0;
  long velocity_resets_ = 0;
  std::unique_ptr<run_files::UncertaintyWriter> uncertainty_;
  double command_ = 0.0;
  double panorama_period_ = 0.0;
  double panorama_max_range_ = 0.0;
  double next_panorama_ = 0.0;
  RateLimitedLog bad_panorama_log_ = RateLimitedLog::once();
  RateLimitedLog bad_profile_log_ = RateLimitedLog::once();
  std::optional<run_files::RunInfo> run_info_;
  std::string output_failure_;  // the first write of the run directory that failed; empty: none
  evaluator::MotorActivity motor_activity_{0.1};
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::EvaluatorComponent, "evaluator")
