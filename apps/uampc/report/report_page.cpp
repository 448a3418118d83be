#include "report/report_page.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "report/experiment_statistics.hpp"
#include "report/run_outputs.hpp"
#include "uampc/plots/svg_plot.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/run_files/time_series.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

using svg::escapeXml;

struct Figure {
  std::string file;
  std::string caption;
};

// Everything the figures of one scene draw from: per controller its first finished run.
class SceneFigures {
 public:
  SceneFigures(const Experiment& experiment, const std::vector<RunResult>& results, std::size_t scene,
               const fs::path& output_directory, const fs::path& report_directory, ReportSummary& summary)
      : experiment_(experiment),
        results_(results),
        scene_(experiment.scenes[scene].name),
        out_(output_directory),
        report_(report_directory),
        summary_(summary) {
    for (const auto& c : experiment.controllers) {
      const RunResult* chosen = nullptr;
      for (const RunResult& r : results) {
        if (r.scene == scene_ && r.controller == c.name && r.finished()) {
          chosen = &r;
          break;
        }
      }
      runs_.push_back(chosen);
    }
  }

  std::vector<Figure> all() {
    std::vector<Figure> figures;
    for (auto make : {&SceneFigures::atePerRun, &SceneFigures::ateOverTime, &SceneFigures::speedOverTime,
                      &SceneFigures::topView, &SceneFigures::uncertaintyMap, &SceneFigures::tradeOff}) {
      if (auto f = (this->*make)(); !f.file.empty()) figures.push_back(f);
    }
    for (Figure& f : panoramaSnapshots()) figures.push_back(std::move(f));
    return figures;
  }

 private:
  fs::path runDirectory(std::size_t controller) const { return out_ / runs_[controller]->directory; }
  std::string seedText(std::size_t controller) const { return "seed " + std::to_string(runs_[controller]->seed); }

  Figure save(const std::string& name, const std::string& svg_text, const std::string& caption) {
    const std::string file = scene_ + "_" + name + ".svg";
    run_files::writeTextFile(report_ / file, svg_text);
    return {file, caption};
  }
  void note(const std::string& text) { summary_.notes.push_back(scene_ + ": " + text); }

  // A run's file read with read(path), or nothing (with a note) when it is missing or malformed.
  template <class Read>
  auto readRunFile(std::size_t controller, const char* file, Read read) -> decltype(read(std::string())) {
    const fs::path path = runDirectory(controller) / file;
    if (!fs::is_regular_file(path)) return {};
    try {
      return read(path.string());
    } catch (const std::exception& e) {
      note(e.what());
      return {};
    }
  }

  // One series per controller over time, from the rows of one of its run's CSV files.
  template <class Row>
  Figure timeSeries(const std::string& name, const char* csv, double Row::*column, const std::string& title,
                    const std::string& y_label, const std::string& caption) {
    svg::LinePlot plot;
    plot.title = title;
    plot.x_label = "sim time, s";
    plot.y_label = y_label;
    for (std::size_t c = 0; c < runs_.size(); ++c) {
      if (!runs_[c]) continue;
      const std::vector<Row> rows = readRunFile(c, csv, run_files::readRows<Row>);
      if (rows.empty()) continue;
      std::vector<double> t, y;
      for (const Row& row : rows) {
        t.push_back(row.time);
        y.push_back(row.*column);
      }
      plot.series.push_back(
          {experiment_.controllers[c].name, std::move(t), std::move(y), svg::paletteColour(c), false, 1.5});
    }
    if (plot.series.empty()) {
      note(std::string("no ") + csv + " in any run: no figure '" + title + "'");
      return {};
    }
    return save(name, svg::render(plot), caption);
  }

  // Every finished run's ATE, one box per controller: how the seeds spread, not only their mean.
  Figure atePerRun() {
    svg::BoxPlot plot;
    plot.title = scene_ + ": ATE of every run";
    plot.y_label = "ATE, m";
    plot.marked_label = "lost track";
    int values = 0;
    for (std::size_t c = 0; c < experiment_.controllers.size(); ++c) {
      svg::Box box{experiment_.controllers[c].name, {}, {}, svg::paletteColour(c)};
      for (const RunResult& r : results_) {
        if (r.scene != scene_ || r.controller != box.label || !r.finished() || !std::isfinite(r.metrics.ate_m))
          continue;
        box.values.push_back(r.metrics.ate_m);
        box.marked.push_back(std::isfinite(r.metrics.runaway_time_s));
        ++values;
      }
      plot.boxes.push_back(std::move(box));
    }
    if (values == 0) {
      note("no finished run with an ATE: no box plot");
      return {};
    }
    return save("ate_boxes", svg::render(plot),
                "ATE of every finished run (dots), per controller: the box spans the first to the third quartile, "
                "the thick line is the median, whiskers reach the furthest run within 1.5 box heights; red rings "
                "are runs that lost track. " +
                    std::string(svg::usesLogScale(plot) ? "Logarithmic scale: the ATEs span more than a factor 20."
                                                        : "Linear scale from zero."));
  }

  Figure ateOverTime() {
    return timeSeries("ate", run_files::kAteFile, &run_files::AteRow::ate_m, scene_ + ": position error over time",
                      "position error, m",
                      "Position error (unaligned, as the paper's ATE) over time, one run per controller (its first "
                      "finished seed).");
  }

  Figure speedOverTime() {
    return timeSeries("speed", run_files::kMotorFile, &run_files::MotorRow::omega, scene_ + ": motor speed over time",
                      "motor speed, rad/s", "Motor speed from the encoder over time, one run per controller.");
  }

  Figure topView() {
    // Ground truth and the map from the controller under test if it ran, else the first that did.
    std::size_t reference = runs_.size();
    for (std::size_t c = 0; c < runs_.size(); ++c) {
      if (runs_[c] && (reference == runs_.size() || experiment_.controllers[c].name == experiment_.subject))
        reference = c;
    }
    if (reference == runs_.size()) {
      note("no finished run: no top view");
      return {};
    }
    svg::LinePlot plot;
    plot.title = scene_ + ": trajectories from above";
    plot.x_label = "x, m";
    plot.y_label = "y, m";
    plot.equal_aspect = true;
    plot.height = 620;
    const Footprint footprint =
        readVoxelFootprint((runDirectory(reference) / run_files::kScannedVoxelsFile).string(), 1.0, 250);
    const int most = footprint.count.empty() ? 1 : *std::max_element(footprint.count.begin(), footprint.count.end());
    for (std::size_t i = 0; i < footprint.x.size(); ++i) {
      // Darker where a column holds more voxels (walls, trees) than where it holds few (ground).
      const double share = std::log1p(footprint.count[i]) / std::log1p(most);
      const int grey = 235 - static_cast<int>(std::lround(4 * share)) * 25;
      char fill[8];
      std::snprintf(fill, sizeof(fill), "#%02x%02x%02x", grey, grey, grey);
      plot.background.push_back(
          {footprint.x[i], footprint.y[i], footprint.x[i] + footprint.cell, footprint.y[i] + footprint.cell, fill});
    }
    const TrajectoryXY truth = readRunFile(reference, run_files::kGroundTruthFile, readTumPositions);
    plot.series.push_back({"ground truth", truth.x, truth.y, "#000000", false, 3.0});
    for (std::size_t c = 0; c < runs_.size(); ++c) {
      if (!runs_[c]) continue;
      const TrajectoryXY estimate = readRunFile(c, run_files::kEstimateFile, readTumPositions);
      plot.series.push_back(
          {experiment_.controllers[c].name, estimate.x, estimate.y, svg::paletteColour(c), false, 1.5});
    }
    return save("top_view", svg::render(plot),
                "Estimated trajectories (one run per controller) and ground truth from above, over the voxels scanned "
                "in the " +
                    experiment_.controllers[reference].name + " run (grey: darker columns hold more voxels).");
  }

  // The controller under test's index in runs_, or runs_.size() if it has no finished run.
  std::size_t subjectRun() const {
    for (std::size_t c = 0; c < runs_.size(); ++c) {
      if (runs_[c] && experiment_.controllers[c].name == experiment_.subject) return c;
    }
    return runs_.size();
  }

  // Up to four of the subject run's panorama snapshots (evaluator: panorama/*.png), evenly spread
  // over the run, copied next to the page.
  std::vector<Figure> panoramaSnapshots() {
    const std::size_t subject = subjectRun();
    if (subject == runs_.size()) return {};
    const fs::path directory = runDirectory(subject) / run_files::kPanoramaDirectory;
    std::vector<fs::path> snapshots;
    std::error_code missing;
    for (const auto& entry : fs::directory_iterator(directory, missing)) {
      if (run_files::panoramaSnapshotTime(entry.path().filename().string())) snapshots.push_back(entry.path());
    }
    if (snapshots.empty()) {
      note("the " + experiment_.subject + " run wrote no panorama snapshots (the evaluator's panorama_period)");
      return {};
    }
    std::sort(snapshots.begin(), snapshots.end());  // names carry the zero-padded sim time
    constexpr std::size_t kShown = 4;
    std::vector<Figure> figures;
    for (std::size_t k = 0; k < std::min(kShown, snapshots.size()); ++k) {
      const fs::path& source = snapshots[k * (snapshots.size() - 1) / std::max<std::size_t>(1, kShown - 1)];
      const std::string file = scene_ + "_" + source.filename().string();
      fs::copy_file(source, report_ / file, fs::copy_options::overwrite_existing);
      figures.push_back({file, "Panoramic depth map (Eq. 5) the " + experiment_.subject + " controller planned on at " +
                                   *run_files::panoramaSnapshotTime(source.filename().string()) + " s of sim time (" +
                                   seedText(subject) +
                                   "): columns are azimuth around the base over 2\xcf\x80, rows elevation from the "
                                   "zenith (top) to the nadir; bright is near, dark blue far, black nothing in the "
                                   "LO's local map."});
      if (snapshots.size() == 1) break;
    }
    return figures;
  }

  Figure uncertaintyMap() {
    const std::size_t subject = subjectRun();
    if (subject == runs_.size()) {
      note("no finished " + experiment_.subject + " run: no U(theta) map");
      return {};
    }
    const std::vector<run_files::UncertaintyRow> table =
        readRunFile(subject, run_files::kUncertaintyFile, run_files::readUncertainty);
    std::vector<const run_files::UncertaintyRow*> rows;
    for (const auto& row : table) {
      if (!row.samples.empty() && std::isfinite(row.time) && std::isfinite(row.delta_theta) && row.delta_theta > 0)
        rows.push_back(&row);
    }
    if (rows.empty()) {
      note(std::string(run_files::kUncertaintyFile) + " of " + experiment_.subject + " is empty: no U(theta) map");
      return {};
    }
    const std::size_t samples = rows.front()->samples.size();
    const double delta = rows.front()->delta_theta;
    // At most 300 columns: neighbouring control steps are averaged (in log U).
    const std::size_t group = (rows.size() + 299) / 300;
    svg::HeatMap map;
    map.title = scene_ + ": predicted uncertainty U over one turn, " + experiment_.subject;
    map.x_label = "sim time, s";
    map.y_label = "angle from the turn's start, rad";
    map.value_label = "log10 U";
    for (std::size_t k = 0; k <= samples; ++k) map.y_edges.push_back(static_cast<double>(k) * delta);
    const double last_step = rows.size() > 1 ? rows.back()->time - rows[rows.size() - 2]->time : 0.1;
    std::vector<double> column_values;
    for (std::size_t begin = 0; begin < rows.size(); begin += group) {
      const std::size_t end = std::min(rows.size(), begin + group);
      map.x_edges.push_back(rows[begin]->time);
      for (std::size_t k = 0; k < samples; ++k) {
        double sum = 0;
        int n = 0;
        for (std::size_t r = begin; r < end; ++r) {
          const double u = k < rows[r]->samples.size() ? rows[r]->samples[k] : NAN;
          if (std::isfinite(u) && u > 0) sum += std::log10(u), ++n;
        }
        column_values.push_back(n ? sum / n : NAN);
      }
    }
    map.x_edges.push_back(rows.back()->time + std::max(last_step, 1e-3));
    const std::size_t nx = map.x_edges.size() - 1;
    map.values.assign(nx * samples, NAN);
    for (std::size_t ix = 0; ix < nx; ++ix) {
      for (std::size_t k = 0; k < samples; ++k) map.values[k * nx + ix] = column_values[ix * samples + k];
    }
    const char* labels[] = {"0", "\xcf\x80/2", "\xcf\x80", "3\xcf\x80/2", "2\xcf\x80"};
    for (int q = 0; q <= 4; ++q) {
      if (q * M_PI / 2 <= samples * delta + 1e-9) map.y_ticks.emplace_back(q * M_PI / 2, labels[q]);
    }
    return save("uncertainty", svg::render(map),
                "U(theta) as the " + experiment_.subject + " controller sampled it at each control step (" +
                    seedText(subject) +
                    "): x is time, y the LiDAR's direction from the start of the predicted turn, "
                    "colour log10 of U (lower: better constrained).");
  }

  Figure tradeOff() {
    svg::LinePlot plot;
    plot.title = scene_ + ": ATE against CMPLT, every run";
    plot.x_label = "CMPLT, voxels per 5 s window";
    plot.y_label = "ATE, m";
    bool any = false;
    for (std::size_t c = 0; c < experiment_.controllers.size(); ++c) {
      svg::Series s{experiment_.controllers[c].name, {}, {}, svg::paletteColour(c), true, 5.0};
      for (const RunResult& r : results_) {
        if (r.scene != scene_ || r.controller != experiment_.controllers[c].name || !r.finished()) continue;
        if (!std::isfinite(r.metrics.cmplt) || !std::isfinite(r.metrics.ate_m)) continue;
        s.x.push_back(r.metrics.cmplt);
        s.y.push_back(r.metrics.ate_m);
      }
      any = any || !s.x.empty();
      plot.series.push_back(std::move(s));
    }
    if (!any) {
      note("no run has both ATE and CMPLT (runs shorter than one 5 s window have no CMPLT): no trade-off figure");
      return {};
    }
    return save("tradeoff", svg::render(plot),
                "Every run as a point: lower is more accurate, further right scans more. The paper's claim is UA-MPC "
                "well below constant speed at nearly the same CMPLT.");
  }

  const Experiment& experiment_;
  const std::vector<RunResult>& results_;
  std::string scene_;
  fs::path out_, report_;
  ReportSummary& summary_;
  std::vector<const RunResult*> runs_;  // per controller; nullptr if none finished
};

std::string summaryTable(const ResultsTable& t) {
  std::string h = "<table>\n<tr><th>controller</th>";
  for (const auto& s : t.scenes) h += "<th>" + escapeXml(s) + " ATE m</th><th>" + escapeXml(s) + " CMPLT</th>";
  h += "<th>ATE sum m</th><th>ATE sum / " + escapeXml(t.baseline) + "</th>";
  for (const auto& s : t.scenes) h += "<th>" + escapeXml(s) + " CMPLT / " + escapeXml(t.baseline) + "</th>";
  h += "</tr>\n";
  for (std::size_t c = 0; c < t.controllers.size(); ++c) {
    h += std::string("<tr") + (static_cast<int>(c) == t.subject_index ? " class=\"subject\"" : "") + "><td>" +
         escapeXml(t.controllers[c]) + "</td>";
    for (std::size_t s = 0; s < t.scenes.size(); ++s) {
      h += "<td>" + formatAte(t.ate[c][s], t.seeds) + "</td><td>" + formatCmplt(t.cmplt[c][s], t.seeds) + "</td>";
    }
    char sum[32];
    std::snprintf(sum, sizeof(sum), "%.2f", t.ate_sum[c]);
    h += "<td>" + std::string(std::isfinite(t.ate_sum[c]) ? sum : "n/a") + "</td><td>" +
         formatRatio(t.ate_sum_ratio[c]) + "</td>";
    for (std::size_t s = 0; s < t.scenes.size(); ++s) h += "<td>" + formatRatio(t.cmplt_ratio[c][s]) + "</td>";
    h += "</tr>\n";
  }
  return h + "</table>\n";
}

std::string htmlTable(const TextTable& table) {
  std::string h = "<table>\n<tr>";
  for (const auto& cell : table.header) h += "<th>" + escapeXml(cell) + "</th>";
  h += "</tr>\n";
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    h += table.emphasised[r] ? "<tr class=\"pooled\">" : "<tr>";
    for (const auto& cell : table.rows[r]) h += "<td>" + escapeXml(cell) + "</td>";
    h += "</tr>\n";
  }
  return h + "</table>\n";
}

// The per-scene figures and the paired comparison of results.md.
std::string statisticsSection(const ExperimentStatistics& st) {
  std::string h = "<h2>Per scene and controller</h2>\n<p>" + escapeXml(cellTableExplanation()) + "</p>\n" +
                  htmlTable(cellTable(st)) + "<h2>Paired comparison</h2>\n";
  if (st.subject.empty()) return h + "<p>No controller under test among the controllers.</p>\n";
  return h + "<p>" + escapeXml(comparisonExplanation(st.subject)) + "</p>\n<p>" + escapeXml(kFewPairsNote) + "</p>\n" +
         htmlTable(comparisonTable(st));
}

std::string runsTable(const std::vector<RunResult>& results) {
  std::string h =
      "<table>\n<tr><th>scene</th><th>controller</th><th>seed</th><th>status</th><th>ATE m</th>"
      "<th>CMPLT</th><th>real-time factor</th><th>wall s</th><th>log</th></tr>\n";
  auto num = [](double v, const char* format) {
    char b[32];
    std::snprintf(b, sizeof(b), format, v);
    return std::isfinite(v) ? std::string(b) : std::string("n/a");
  };
  for (const RunResult& r : results) {
    h += "<tr><td>" + escapeXml(r.scene) + "</td><td>" + escapeXml(r.controller) + "</td><td>" +
         std::to_string(r.seed) + "</td><td class=\"" + statusName(r.status) + "\">" + statusName(r.status) +
         (r.failure.empty() ? "" : ": " + escapeXml(r.failure)) + "</td><td>" + num(r.metrics.ate_m, "%.3f") +
         "</td><td>" + num(r.metrics.cmplt, "%.0f") + "</td><td>" + num(r.real_time_factor, "%.2f") + "</td><td>" +
         num(r.wall_time_s, "%.1f") + "</td><td><a href=\"../" + escapeXml(r.directory) +
         "/run.log\">run.log</a></td></tr>\n";
  }
  return h + "</table>\n";
}

const char* const kStyle = R"(<style>
body { font-family: sans-serif; margin: 2em auto; max-width: 1100px; color: #222; }
table { border-collapse: collapse; margin: 1em 0; font-size: 14px; }
th, td { border: 1px solid #ccc; padding: 4px 8px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
tr.subject, tr.pooled { font-weight: bold; }
td.failed { color: #b00; } td.not_run { color: #888; }
figure { margin: 2em 0; } figcaption { color: #555; max-width: 760px; }
img[src$=".png"] { width: 720px; image-rendering: pixelated; } /* 180 x 90 panoramas, enlarged */
#figure-check { color: #888; font-size: 12px; }
</style>
)";

// Counts figures that decoded (complete with a natural width) once everything has loaded.
const char* const kFigureCheck = R"(<script>
window.addEventListener('load', function () {
  var images = document.querySelectorAll('img');
  var loaded = 0;
  for (var i = 0; i < images.length; ++i) {
    if (images[i].complete && images[i].naturalWidth > 0) ++loaded;
  }
  document.getElementById('figure-check').textContent = 'figures loaded: ' + loaded + ' of ' + images.length;
});
</script>
)";

}  // namespace

ReportSummary writeReport(const Experiment& experiment, const std::vector<RunResult>& results,
                          const ResultsTable& table, const std::string& output_directory) {
  ReportSummary summary;
  const fs::path report = fs::path(output_directory) / "report";
  fs::create_directories(report);
  for (const auto& entry : fs::directory_iterator(report)) {
    const auto extension = entry.path().extension();
    if (extension == ".svg" || extension == ".png") fs::remove(entry.path());  // figures of an earlier report
  }
  std::string body;
  for (std::size_t s = 0; s < experiment.scenes.size(); ++s) {
    body += "<h2>" + escapeXml(experiment.scenes[s].name) + "</h2>\n";
    for (const Figure& f : SceneFigures(experiment, results, s, output_directory, report, summary).all()) {
      body += "<figure><img src=\"" + escapeXml(f.file) + "\" alt=\"" + escapeXml(f.file) + "\"><figcaption>" +
              escapeXml(f.caption) + "</figcaption></figure>\n";
      ++summary.figures;
    }
  }
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Experiment " +
                     escapeXml(experiment.name) + "</title>\n" + kStyle + "</head>\n<body>\n<h1>Experiment " +
                     escapeXml(experiment.name) + "</h1>\n<p>From <code>" + escapeXml(experiment.file) + "</code>; " +
                     std::to_string(table.seeds) +
                     " seed(s) per cell, means over seeds. ATE: RMSE of the unaligned "
                     "positions. CMPLT: 0.5 m voxels scanned per 5 s window (n/a: no complete window).</p>\n" +
                     summaryTable(table) + "<p>" + escapeXml(headline(table)) + "</p>\n" +
                     statisticsSection(computeStatistics(experiment, results)) + body + "<h2>Runs</h2>\n" +
                     runsTable(results) + "<h2>Notes</h2>\n<ul>\n";
  for (const auto& n : summary.notes) html += "<li>" + escapeXml(n) + "</li>\n";
  html += "</ul>\n<p id=\"figure-check\">figures loaded: not checked yet</p>\n" + std::string(kFigureCheck) +
          "</body>\n</html>\n";
  run_files::writeTextFile(report / "index.html", html);
  return summary;
}

}  // namespace uampc::app
