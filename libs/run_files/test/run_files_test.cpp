// The run directory's schema: what the writers write, the readers read back (round trips), in the
// text the evaluator has always written (metrics.json is compared byte for byte across versions).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "full_disk.hpp"
#include "uampc/run_files/json_text.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_info.hpp"
#include "uampc/run_files/run_progress.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/run_files/time_series.hpp"

namespace uampc::run_files {
namespace {

namespace fs = std::filesystem;

std::string freshDirectory(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("run_files_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string contentOf(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

MetricsDocument sampleMetrics() {
  MetricsDocument m;
  m.sim_time = 20;
  m.trajectory.estimates = 201;
  m.trajectory.paired = 200;
  m.trajectory.unpaired = 1;
  m.trajectory.distance_m = 14.697838943985376;
  m.trajectory.ate.unaligned_m = {200, 0.1, 0.09, 0.08, 0.3};
  m.trajectory.ate.aligned_m = {200, 0.05, kNotANumber, 0.04, 1e-300};
  RpeSummary ten;
  ten.segment_length_m = 10;
  ten.translation_m = {12, 0.25, 0.2, 0.2, 0.5};
  RpeSummary hundred;
  hundred.segment_length_m = 100;  // no segment that long: no pairs, NaN figures
  m.trajectory.rpe = {ten, hundred};
  m.trajectory.speed_error.max_m_s = 3.6;
  m.trajectory.speed_error.first_runaway_time = 7.25;
  m.cmplt.cmplt = 1234.5;
  m.cmplt.windows = 4;
  m.cmplt.complete_windows = 3;
  m.cmplt_ground_truth.cmplt = kNotANumber;
  m.motor.mean_speed = 3.6000000000000001;
  m.lo.lost_frames = 2;
  m.lo.frames = 900;
  m.lo.degenerate_frames = 850;
  m.lo.rejected_updates = -1;
  return m;
}

void expectSameSummary(const ErrorSummary& a, const ErrorSummary& b) {
  EXPECT_EQ(a.count, b.count);
  for (auto field : {&ErrorSummary::rmse, &ErrorSummary::mean, &ErrorSummary::median, &ErrorSummary::max}) {
    if (std::isnan(a.*field))
      EXPECT_TRUE(std::isnan(b.*field));
    else
      EXPECT_EQ(a.*field, b.*field);
  }
}

TEST(MetricsFile, ReadsBackWhatItWrote) {
  const std::string path = inDirectory(freshDirectory("metrics"), kMetricsFile);
  const MetricsDocument written = sampleMetrics();
  writeMetricsFile(path, written);
  const std::optional<MetricsDocument> read = readMetricsFile(path);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->sim_time, 20.0);
  EXPECT_EQ(read->trajectory.estimates, 201u);
  EXPECT_EQ(read->trajectory.unpaired, 1u);
  EXPECT_EQ(read->trajectory.distance_m, 14.697838943985376);  // every digit survives
  expectSameSummary(read->trajectory.ate.unaligned_m, written.trajectory.ate.unaligned_m);
  expectSameSummary(read->trajectory.ate.aligned_m, written.trajectory.ate.aligned_m);
  ASSERT_EQ(read->trajectory.rpe.size(), 2u);
  ASSERT_NE(read->trajectory.rpeOver(10), nullptr);
  expectSameSummary(read->trajectory.rpeOver(10)->translation_m, written.trajectory.rpe[0].translation_m);
  EXPECT_TRUE(std::isnan(read->trajectory.rpeOver(100)->translation_m.rmse));
  EXPECT_EQ(read->trajectory.rpeOver(50), nullptr);
  EXPECT_EQ(read->trajectory.speed_error.first_runaway_time, 7.25);
  EXPECT_EQ(read->cmplt.cmplt, 1234.5);
  EXPECT_EQ(read->cmplt.complete_windows, 3u);
  EXPECT_TRUE(std::isnan(read->cmplt_ground_truth.cmplt));
  EXPECT_EQ(read->motor.mean_speed, 3.6);
  EXPECT_TRUE(std::isnan(read->motor.speed_std));
  EXPECT_FALSE(read->lo.first_lost_time);
  EXPECT_EQ(read->lo.lost_frames, 2);
  EXPECT_EQ(read->lo.frames, 900);
  EXPECT_EQ(read->lo.degenerate_frames, 850);
  EXPECT_EQ(read->lo.rejected_updates, -1);
}

TEST(MetricsFile, PrintsAsTheEvaluatorAlwaysHas) {
  // Whole numbers without ".0", shortest round-trip digits, null for NaN, optional keys absent,
  // "rpe_<length>m" keys in place, nested objects indented by two.
  const std::string path = inDirectory(freshDirectory("metrics_text"), kMetricsFile);
  MetricsDocument m = sampleMetrics();
  m.trajectory.speed_error.first_runaway_time.reset();
  writeMetricsFile(path, m);
  const std::string text = contentOf(path);
  EXPECT_EQ(text.rfind("{\n  \"sim_time\": 20,\n  \"trajectory\": {\n    \"estimates\": 201,\n", 0), 0u) << text;
  EXPECT_NE(text.find("\"distance_m\": 14.697838943985376,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"aligned_m\": {\n        \"count\": 200,\n        \"rmse\": 0.05,\n        \"mean\": null,"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\"max\": 1e-300"), std::string::npos) << text;
  EXPECT_NE(text.find("\"rpe_10m\": {\n      \"segment_length_m\": 10,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"rpe_100m\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"speed_error\": {\n      \"max_m_s\": 3.6\n    }"), std::string::npos) << text;
  EXPECT_NE(text.find("\"mean_speed\": 3.6,"), std::string::npos) << text;
  EXPECT_EQ(text.find("first_lost_time"), std::string::npos) << text;
  const std::string tail =
      "  \"lo\": {\n    \"lost_frames\": 2,\n    \"rejected_updates\": -1,\n    \"velocity_resets\": 0,\n    \"frames\": 900,\n"
      "    \"degenerate_frames\": 850\n  }\n}\n";
  EXPECT_EQ(text.substr(text.size() - tail.size()), tail) << text;
}

TEST(MetricsFile, UnfinishedRunsHaveNone) {
  const std::string dir = freshDirectory("metrics_missing");
  EXPECT_FALSE(readMetricsFile(inDirectory(dir, kMetricsFile)));
  writeText(inDirectory(dir, kMetricsFile), "{\n  \"sim_time\": 20,\n  \"traj");  // torn
  EXPECT_FALSE(readMetricsFile(inDirectory(dir, kMetricsFile)));
  writeText(inDirectory(dir, kMetricsFile), "{\"cmplt\": {}}");  // not a metrics document
  EXPECT_FALSE(readMetricsFile(inDirectory(dir, kMetricsFile)));
  // An older evaluator's: what it lacks reads as unknown, wrong types too.
  writeText(inDirectory(dir, kMetricsFile), "{\"sim_time\": 5, \"motor\": {\"mean_speed\": \"fast\"}}");
  const auto old = readMetricsFile(inDirectory(dir, kMetricsFile));
  ASSERT_TRUE(old);
  EXPECT_EQ(old->sim_time, 5.0);
  EXPECT_TRUE(std::isnan(old->motor.mean_speed));
  EXPECT_TRUE(std::isnan(old->trajectory.distance_m));
  EXPECT_TRUE(old->trajectory.rpe.empty());
}

// A run's end, as the evaluator and an experiment both judge it: up to a step (and a rounding)
// short of the duration, never beyond it short, never for NaN.
TEST(RunInfo, ARunReachesItsEndUpToALastStepShort) {
  EXPECT_TRUE(run_files::reachesEnd(30.0, 30.0, 0.01));
  EXPECT_TRUE(run_files::reachesEnd(29.99, 30.0, 0.01));
  EXPECT_TRUE(run_files::reachesEnd(29.99 - 5e-7, 30.0, 0.01));  // a sum of steps, a rounding short
  EXPECT_FALSE(run_files::reachesEnd(29.98, 30.0, 0.01));
  EXPECT_FALSE(run_files::reachesEnd(13.9, 20.0, 0.01));
  EXPECT_FALSE(run_files::reachesEnd(std::nan(""), 30.0, 0.01));
}

TEST(JsonText, ListsAndStrings) {
  Json json = Json::object();
  json["name"] = "ua \"mpc\"\n\\ \x01";
  json["seeds"] = {1, 2};
  json["ratios"] = {0.5, std::nan(""), -2.0};
  json["runs"] = Json::array({Json{{"seed", 1}}, Json{{"seed", 2}}});
  json["none"] = Json::array();
  json["empty"] = Json::object();
  EXPECT_EQ(dumpJson(json),
            "{\n  \"name\": \"ua \\\"mpc\\\"\\n\\\\ \\u0001\",\n  \"seeds\": [1, 2],\n  \"ratios\": [0.5, null, -2],\n"
            "  \"runs\": [\n    {\n      \"seed\": 1\n    },\n    {\n      \"seed\": 2\n    }\n  ],\n"
            "  \"none\": [],\n  \"empty\": {}\n}");
  // What it prints, nlohmann reads back.
  EXPECT_EQ(Json::parse(dumpJson(json))["runs"][1]["seed"], 2);
}

TEST(TimeSeries, RowsReadBackByColumnName) {
  const std::string dir = freshDirectory("series");
  const std::string ate = inDirectory(dir, kAteFile);
  writeRows<AteRow>(ate, {{1.0, 0.5, 0.25}, {1.1, 1e20, std::nan("")}});
  EXPECT_EQ(contentOf(ate), "time,ate_m,ate_aligned_m\n1,0.5,0.25\n1.1,1e+20,nan\n");
  const std::vector<AteRow> rows = readRows<AteRow>(ate);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].time, 1.1);
  EXPECT_EQ(rows[1].ate_m, 1e20);
  EXPECT_TRUE(std::isnan(rows[1].ate_aligned_m));

  CsvWriter short_rows(inDirectory(dir, "short.csv"), {"a", "b"});
  EXPECT_THROW(short_rows.addRow({1.0}), std::invalid_argument);

  const std::string windows = inDirectory(dir, kCompletenessWindowsFile);
  writeRows<CompletenessWindowRow>(windows, {{2, 10, 15, 7, 50, 1000, true}});
  EXPECT_EQ(contentOf(windows), "window,start,end,voxels,scans,points,complete\n2,10,15,7,50,1000,1\n");
  EXPECT_TRUE(readRows<CompletenessWindowRow>(windows).at(0).complete);

  // Columns are found by name, not by place.
  const std::string motor = inDirectory(dir, kMotorFile);
  writeText(motor, "omega,time,command,theta\n3.5,0.1,3.6,0.35\n");
  const auto motor_rows = readRows<MotorRow>(motor);
  EXPECT_EQ(motor_rows.at(0).time, 0.1);
  EXPECT_EQ(motor_rows.at(0).omega, 3.5);
}

TEST(TimeSeries, MalformedFilesAreNamedWithTheirLine) {
  const std::string dir = freshDirectory("series_bad");
  const std::string motor = inDirectory(dir, kMotorFile);
  auto expectError = [](const std::function<void()>& read, const std::string& wanted) {
    try {
      read();
      ADD_FAILURE() << "no error, expected one naming " << wanted;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(wanted), std::string::npos) << e.what();
    }
  };
  expectError([&] { readRows<MotorRow>(motor); }, motor);  // missing
  writeText(motor, "time,theta,omega,command\n0.1,0.2,0.3,0.4\n0.2,x,0.3,0.4\n");
  expectError([&] { readRows<MotorRow>(motor); }, motor + ":3: 'x' is not a number");
  writeText(motor, "time,theta,omega\n0.1,0.2,0.3\n");
  expectError([&] { readRows<MotorRow>(motor); }, "no column 'command'");
  writeText(motor, "time,theta,omega,command\n0.1,0.2,0.3\n");
  expectError([&] { readRows<MotorRow>(motor); }, motor + ":2: no value for column 'command'");
}

TEST(TimeSeries, UncertaintyAndTimingsInTheirOwnPrecision) {
  const std::string dir = freshDirectory("logs");
  const std::string u = inDirectory(dir, kUncertaintyFile);
  {
    UncertaintyWriter writer(u);
    writer.add({0.1, 0.25, 0.5, 3.6, {1.0, 0.123456789123}});
  }
  EXPECT_EQ(
      contentOf(u),
      "time,theta_start,delta_theta,command,u_000,u_001\n0.100000000,0.25,0.5,3.6000000000000001,1,0.123456789\n");
  const auto rows = readUncertainty(u);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].command, 3.6);
  EXPECT_EQ(rows[0].samples, (std::vector<double>{1.0, 0.123456789}));

  const std::string t = inDirectory(dir, kTimingsFile);
  {
    TimingsWriter writer(t);
    writer.add({2.5, "lo", "registration_ms", 1.25});
  }
  EXPECT_EQ(contentOf(t), "time,source,name,value\n2.500000000,lo,registration_ms,1.25\n");
  const auto timings = readTimings(t);
  ASSERT_EQ(timings.size(), 1u);
  EXPECT_EQ(timings[0].source, "lo");
  EXPECT_EQ(timings[0].name, "registration_ms");
  EXPECT_EQ(timings[0].value, 1.25);
}

// The number of comma-separated fields of every line of a file.
std::vector<std::size_t> fieldsPerLine(const std::string& path) {
  std::vector<std::size_t> counts;
  std::stringstream lines(contentOf(path));
  for (std::string line; std::getline(lines, line);) counts.push_back(std::count(line.begin(), line.end(), ',') + 1u);
  return counts;
}

TEST(TimeSeries, UncertaintyIsRectangularWithAColumnPerSample) {
  const std::string dir = freshDirectory("uncertainty");
  const std::string u = inDirectory(dir, kUncertaintyFile);
  UncertaintyRow row{0.1, 0.0, 2 * M_PI / 72, 3.6, std::vector<double>(72, 0.5)};
  {
    UncertaintyWriter writer(u);
    writer.add(row);
    row.time = 0.2;
    writer.add(row);
    UncertaintyRow shorter = row;
    shorter.samples.pop_back();
    try {
      writer.add(shorter);
      ADD_FAILURE() << "a row of 71 samples was accepted under 72 columns";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(u + ": a row of 71 U samples"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(fieldsPerLine(u), (std::vector<std::size_t>{76, 76, 76}));  // the refused row left out
  const CsvTable table = readCsv(u);
  EXPECT_EQ(table.columns[4], "u_000");
  EXPECT_EQ(table.columns[75], "u_071");
  EXPECT_EQ(uncertaintySampleColumn(1234), "u_1234");
  const auto rows = readUncertainty(u);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].time, 0.2);
  EXPECT_EQ(rows[1].samples, std::vector<double>(72, 0.5));

  // A controller that never sampled: the header alone, without sample columns.
  const std::string none = inDirectory(dir, "none.csv");
  { UncertaintyWriter writer(none); }
  EXPECT_EQ(contentOf(none), "time,theta_start,delta_theta,command\n");
  EXPECT_TRUE(readUncertainty(none).empty());
}

TEST(TimeSeries, UncertaintyReaderChecksTheShapeAndReadsOlderRuns) {
  const std::string dir = freshDirectory("uncertainty_read");
  const std::string u = inDirectory(dir, kUncertaintyFile);
  auto expectError = [&](const std::string& text, const std::string& wanted) {
    writeText(u, text);
    try {
      readUncertainty(u);
      ADD_FAILURE() << "no error for:\n" << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(wanted), std::string::npos) << e.what();
    }
  };
  expectError("time,theta_start,delta_theta,command,u_000,u_001\n0.1,0,3.14,3.6,1,2\n0.2,0,3.14,3.6,1\n",
              u + ":3: 5 fields, but the header names 6");
  expectError("time,theta_start,delta_theta,command,u_000,u_002\n", u + ":1: not the header of uncertainty.csv");
  expectError("time,theta_start,delta_theta,command,u_000,u_002\n", "column 6 is 'u_002', expected 'u_001'");
  expectError("theta_start,time,delta_theta,command\n", "column 1 is 'theta_start'");
  // Before it was rectangular: one name for all the samples, rows of any length.
  writeText(u, "time,theta_start,delta_theta,command,samples...\n0.1,0,3.14,3.6,1,2\n0.2,0,2.09,3.6,1,2,3\n");
  const auto legacy = readUncertainty(u);
  ASSERT_EQ(legacy.size(), 2u);
  EXPECT_EQ(legacy[1].samples, (std::vector<double>{1, 2, 3}));
  // Empty: the evaluator stopped before the controller's first profile.
  writeText(u, "");
  EXPECT_TRUE(readUncertainty(u).empty());
}

RunInfo sampleRunInfo() {
  RunInfo info;
  info.scene_copy = kSceneCopyFile;
  info.scene_source = "/scenes/campus \"ua\".yaml";
  info.overrides = {"clock.duration=2", "seed=7"};
  info.started_utc = "2025-01-31T12:00:00Z";
  info.seed = 18446744073709551615u;  // every uint64 seed survives
  info.domain_id = 63;
  info.uampc_version = "v0.3-12-gabcdef0-dirty";
  info.fastdds_version = "2.9.1";
  info.components = Json::parse(R"({"motor": {"type": "motor_bridge", "process": "main",
      "params": {"encoder_rate": 200, "inertia": 0.25, "enabled": true, "topics": ["/a", "/b"]}}})");
  return info;
}

TEST(RunInfoFile, ReadsBackWhatItWrote) {
  const std::string path = inDirectory(freshDirectory("run_info"), kRunInfoFile);
  writeRunInfoFile(path, sampleRunInfo());
  const RunInfo read = readRunInfoFile(path);
  EXPECT_EQ(read.scene_copy, "scene.yaml");
  EXPECT_EQ(read.scene_source, "/scenes/campus \"ua\".yaml");
  EXPECT_EQ(read.overrides, (std::vector<std::string>{"clock.duration=2", "seed=7"}));
  EXPECT_EQ(read.started_utc, "2025-01-31T12:00:00Z");
  EXPECT_EQ(read.seed, 18446744073709551615u);
  EXPECT_EQ(read.domain_id, 63);
  EXPECT_EQ(read.uampc_version, "v0.3-12-gabcdef0-dirty");
  EXPECT_EQ(read.fastdds_version, "2.9.1");
  EXPECT_EQ(read.components, sampleRunInfo().components);
  EXPECT_EQ(read.components["motor"]["params"]["inertia"].get<double>(), 0.25);
}

TEST(RunInfoFile, AMissingOrMistypedKeyIsNamed) {
  const std::string path = inDirectory(freshDirectory("run_info_bad"), kRunInfoFile);
  auto expectError = [&](const std::string& text, const std::string& wanted) {
    writeText(path, text);
    try {
      readRunInfoFile(path);
      ADD_FAILURE() << "no error for " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(wanted), std::string::npos) << e.what();
    }
  };
  Json json = runInfoToJson(sampleRunInfo());
  json.erase("uampc_version");
  expectError(json.dump(), path + ": no key 'uampc_version'");
  json = runInfoToJson(sampleRunInfo());
  json["seed"] = -1;
  expectError(json.dump(), path + ": 'seed' is -1, not of the expected type");
  json["seed"] = 1.5;
  expectError(json.dump(), "'seed' is 1.5");
  json = runInfoToJson(sampleRunInfo());
  json["components"] = Json::array();
  expectError(json.dump(), "'components' is []");
  expectError("[1, 2]", path + ": not a JSON object");
  expectError("{\"scene\": ", path + ": not JSON");
}

TEST(MetricsFile, TheRunObjectComesLastAndReadsBackOnlyWhole) {
  const std::string path = inDirectory(freshDirectory("metrics_run"), kMetricsFile);
  MetricsDocument m = sampleMetrics();
  m.run = sampleRunInfo();
  writeMetricsFile(path, m);
  const std::string text = contentOf(path);
  // The figures print as before, then the run.
  EXPECT_NE(text.find("\"degenerate_frames\": 850\n  },\n  \"run\": {\n    \"scene\": \"scene.yaml\","),
            std::string::npos)
      << text;
  const auto read = readMetricsFile(path);
  ASSERT_TRUE(read && read->run);
  EXPECT_EQ(read->run->seed, 18446744073709551615u);
  EXPECT_EQ(read->run->components, m.run->components);
  // A run object lacking a key: absent, the figures still read.
  Json json = readJsonFile(path);
  json["run"].erase("seed");
  writeText(path, json.dump());
  const auto torn = readMetricsFile(path);
  ASSERT_TRUE(torn);
  EXPECT_FALSE(torn->run);
  EXPECT_EQ(torn->sim_time, 20.0);
  // No run object: none read.
  writeMetricsFile(path, sampleMetrics());
  EXPECT_FALSE(readMetricsFile(path)->run);
}

TEST(RunDirectory, MarkersAndSnapshotNames) {
  const std::string dir = freshDirectory("markers");
  EXPECT_FALSE(readDoneMarker(dir));
  writeDoneMarker(dir, 4.5);
  EXPECT_EQ(readDoneMarker(dir), 4.5);
  EXPECT_EQ(readFailedMarker(dir), "");
  writeFailedMarker(dir, "exit code 1");
  EXPECT_EQ(readFailedMarker(dir), "exit code 1\n");
  EXPECT_EQ(panoramaSnapshotName(4.0), "panorama_00004.0.png");
  EXPECT_EQ(panoramaSnapshotTime(panoramaSnapshotName(123.45)), "00123.5");
  EXPECT_FALSE(panoramaSnapshotTime("scanned_voxels.bt"));
}

TEST(RunProgress, ReadsBackWhatItWrote) {
  const std::string path = inDirectory(freshDirectory("progress"), kProgressFile);
  EXPECT_FALSE(readRunProgress(path));
  writeRunProgress(path, {46.9, 890.0, 10.5, false});
  auto p = readRunProgress(path);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->sim_s, 46.9);
  EXPECT_EQ(p->total_s, 890.0);
  EXPECT_EQ(p->wall_s, 10.5);
  EXPECT_FALSE(p->finished);
  writeRunProgress(path, {890.0, 890.0, 200.0, true});
  EXPECT_TRUE(readRunProgress(path)->finished);
  EXPECT_FALSE(fs::exists(path + ".partial"));
  writeText(path, "{\"sim_s\": 3");  // not this writer's (it renames whole files into place)
  EXPECT_FALSE(readRunProgress(path));
}

// What a full disk does to the files written whole (docs/decisions/run-files-whole-or-absent.md):
// the write fails with the file and the reason named, and leaves the file as it was, or absent,
// never cut (a cut metrics.json or done marker would pass for a complete one). The disk is full
// beyond 100 bytes here (test::ScopedFileSizeLimit, full_disk.hpp: EFBIG where a disk gives ENOSPC).
TEST(WholeFiles, AFileThatCannotBeWrittenWholeIsLeftAsItWas) {
  const std::string dir = freshDirectory("whole_files");
  const std::string path = inDirectory(dir, "report.txt"), existing = inDirectory(dir, "existing.txt");
  writeTextFile(existing, "before\n");
  MetricsDocument metrics;
  metrics.sim_time = 30.0;
  {
    test::ScopedFileSizeLimit full_disk(100);
    for (const std::string& target : {path, existing}) {
      try {
        writeTextFile(target, std::string(1000, 'x'));
        ADD_FAILURE() << "1000 bytes written under a 100-byte limit";
      } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write " + target + ": File too large");
      }
    }
    EXPECT_THROW(writeMetricsFile(inDirectory(dir, kMetricsFile), metrics), std::runtime_error);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(contentOf(existing), "before\n");
  EXPECT_FALSE(fs::exists(inDirectory(dir, kMetricsFile)));
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  {
    test::ScopedFileSizeLimit full_disk(0);
    EXPECT_THROW(writeDoneMarker(dir, 4.5), std::runtime_error);
  }
  EXPECT_FALSE(readDoneMarker(dir));
}

// An append-only log (the Slurm backend's submissions.log and jobs) on a full disk: the append
// fails naming the file, and the file is left with the lines it had, not with part of the new one
// (a job id cut short would read as another job's). /dev/full fails the same append with ENOSPC.
TEST(AppendedFiles, AnAppendThatCannotBeWrittenWholeLeavesTheFileAsItWas) {
  const std::string dir = freshDirectory("appended_files");
  const std::string path = inDirectory(dir, "jobs");
  appendToTextFile(path, "4242\n");
  appendToTextFile(path, "4243\n");
  EXPECT_EQ(contentOf(path), "4242\n4243\n");
  {
    test::ScopedFileSizeLimit full_disk(14);  // room for 4 of the 10 bytes below
    try {
      appendToTextFile(path, "123456789\n");
      ADD_FAILURE() << "an append beyond the file size limit was taken";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "cannot write " + path + ": File too large");
    }
  }
  EXPECT_EQ(contentOf(path), "4242\n4243\n");
  try {
    appendToTextFile("/dev/full", "4244\n");
    ADD_FAILURE() << "an append to /dev/full was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write /dev/full: No space left on device");
  }
  const std::string in_the_way = inDirectory(dir, "a_directory");
  fs::create_directories(in_the_way);
  EXPECT_THROW(appendToTextFile(in_the_way, "x\n"), std::runtime_error);
}

// The files written through a run, on a full disk: /dev/full fails every write with ENOSPC, as a
// disk that has filled up does. The failure shows at the row that overflows the writer's buffer
// (or at close), names the file and the reason, and every row after it fails the same way: a cut
// file does not go on after a gap.
void expectEveryWriteFailsOnceOneHas(const std::function<void()>& add_row, const std::string& what) {
  const std::string wanted = "cannot write /dev/full: No space left on device";
  bool failed = false;
  for (int row = 0; row < 100000 && !failed; ++row) {
    try {
      add_row();
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), wanted) << what;
      failed = true;
    }
  }
  ASSERT_TRUE(failed) << what << ": 100000 rows written to /dev/full without an error";
  try {
    add_row();
    ADD_FAILURE() << what << ": a row after a failed one was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), wanted) << what;
  }
}

TEST(TimeSeries, AFullDiskFailsEveryWriterNamingTheFile) {
  RowWriter<MotorRow> motor("/dev/full");
  expectEveryWriteFailsOnceOneHas([&] { motor.add({1.0, 2.0, 3.0, 3.6}); }, "motor.csv");
  TimingsWriter timings("/dev/full");
  expectEveryWriteFailsOnceOneHas([&] { timings.add({2.5, "lo", "registration_ms", 1.25}); }, "timings.csv");
  UncertaintyWriter uncertainty("/dev/full");
  expectEveryWriteFailsOnceOneHas([&] { uncertainty.add({0.1, 0.0, 0.5, 3.6, std::vector<double>(72, 0.5)}); },
                                  "uncertainty.csv");
  // Rows that fit the buffer fail at close, where they would reach the disk.
  RowWriter<MotorRow> short_file("/dev/full");
  short_file.add({1.0, 2.0, 3.0, 3.6});
  EXPECT_THROW(short_file.close(), std::runtime_error);
}

}  // namespace
}  // namespace uampc::run_files
