// The CSV files of a run (names in run_directory.hpp): one row type each, its columns named once.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "uampc/run_files/csv.hpp"
#include "uampc/run_files/streamed_file.hpp"

namespace uampc::run_files {

// ate.csv: the position error of every paired estimate.
struct AteRow {
  double time = 0.0;           // s
  double ate_m = 0.0;          // unaligned (the paper's ATE)
  double ate_aligned_m = 0.0;  // after the Umeyama alignment
  template <class Row, class Visit>
  static void fields(Row& r, Visit&& visit) {
    visit("time", r.time);
    visit("ate_m", r.ate_m);
    visit("ate_aligned_m", r.ate_aligned_m);
  }
};

// cmplt_windows.csv and cmplt_ground_truth_windows.csv: one CMPLT window a row.
struct CompletenessWindowRow {
  double window = 0.0;  // index
  double start = 0.0;   // s
  double end = 0.0;     // s
  double voxels = 0.0;
  double scans = 0.0;
  double points = 0.0;
  bool complete = false;  // written 0 or 1
  template <class Row, class Visit>
  static void fields(Row& r, Visit&& visit) {
    visit("window", r.window);
    visit("start", r.start);
    visit("end", r.end);
    visit("voxels", r.voxels);
    visit("scans", r.scans);
    visit("points", r.points);
    visit("complete", r.complete);
  }
};

// motor.csv: every encoder state, with the command in force.
struct MotorRow {
  double time = 0.0;     // s
  double theta = 0.0;    // rad
  double omega = 0.0;    // rad/s, measured
  double command = 0.0;  // rad/s
  template <class Row, class Visit>
  static void fields(Row& r, Visit&& visit) {
    visit("time", r.time);
    visit("theta", r.theta);
    visit("omega", r.omega);
    visit("command", r.command);
  }
};

// uncertainty.csv: UA-MPC's U samples over one turn at each control step, one column per sample:
// time,theta_start,delta_theta,command,u_000,u_001,... (sample k at theta_start + k delta_theta).
// Rectangular: every row has as many fields as the header has names. The controller's sample count
// is fixed, so the first row sets the columns.
struct UncertaintyRow {
  double time = 0.0;         // s
  double theta_start = 0.0;  // rad, the angle of samples[0]
  double delta_theta = 0.0;  // rad between samples
  double command = 0.0;      // rad/s
  std::vector<double> samples;
};

// timings.csv: every value the LO and the controller publish on their metrics topics.
struct TimingRow {
  double time = 0.0;  // s
  std::string source, name;
  double value = 0.0;
};

// The two files written line by line through a run in their own precision (times to the
// nanosecond, U samples to 9 digits), as fprintf prints them. Every write is checked
// (streamed_file.hpp): a failed one throws std::runtime_error "cannot write PATH: REASON", from
// the constructor, add() or close().
// The header is written with the first row (whose sample count names the columns), or without
// sample columns when the writer ends having had none; until then the file is empty.
class UncertaintyWriter {
 public:
  explicit UncertaintyWriter(const std::string& path);
  ~UncertaintyWriter();  // close() without a word about failures
  // Throws std::invalid_argument naming the file when the row's sample count differs from the
  // first row's (the columns are fixed by then); nothing is written then.
  void add(const UncertaintyRow& row);
  void close();

 private:
  StreamedFile file_;
  std::optional<std::size_t> samples_;  // set by the first row
};

class TimingsWriter {
 public:
  explicit TimingsWriter(const std::string& path);
  void add(const TimingRow& row);
  void close() { file_.close(); }

 private:
  StreamedFile file_;
};

// The name of sample k's column: "u_" and k, zero-padded to 3 digits ("u_007").
std::string uncertaintySampleColumn(std::size_t k);

// Throw std::runtime_error naming path:line on a malformed row. readUncertainty also reads the
// files of runs made before uncertainty.csv was rectangular (header "...,command,samples...", rows
// of any length), and an empty file (the evaluator stopped before the first row) as no rows.
std::vector<UncertaintyRow> readUncertainty(const std::string& path);
std::vector<TimingRow> readTimings(const std::string& path);

}  // namespace uampc::run_files
