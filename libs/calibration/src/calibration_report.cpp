#include "uampc/calibration/calibration_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "uampc/plots/svg_plot.hpp"

namespace uampc::calibration {
namespace {

enum class Kind { kAngle, kOffset, kTime };

Kind kindOf(const ParameterEstimate& p) {
  if (p.name.size() > 4 && p.name.compare(p.name.size() - 4, 4, "_deg") == 0) return Kind::kAngle;
  if (p.name == "time_offset") return Kind::kTime;
  return Kind::kOffset;
}

// Each kind in the unit a reader thinks in: degrees, millimetres, milliseconds.
std::string shown(const ParameterEstimate& p, double value, int extra_digits = 0) {
  if (std::abs(value) < 1e-9) value = 0.0;  // no "-0.000"
  std::ostringstream s;
  s.setf(std::ios::fixed);
  switch (kindOf(p)) {
    case Kind::kAngle:
      s.precision(3 + extra_digits);
      s << value << " deg";
      break;
    case Kind::kOffset:
      s.precision(2 + extra_digits);
      s << value * 1e3 << " mm";
      break;
    case Kind::kTime:
      s.precision(3 + extra_digits);
      s << value * 1e3 << " ms";
      break;
  }
  return s.str();
}

std::string number(double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  return s.str();
}

const ParameterEstimate& named(const CalibrationResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p;
  throw std::logic_error("calibration result without " + name);
}

// The value the rig block gets: the estimate when trusted, the believed value otherwise.
double kept(const ParameterEstimate& p, const TrustLimits& limits) {
  return p.estimated && trusted(p, limits) ? p.value : p.believed;
}

}  // namespace

bool trusted(const ParameterEstimate& p, const TrustLimits& limits) {
  if (!std::isfinite(p.stddev)) return false;
  switch (kindOf(p)) {
    case Kind::kAngle:
      return p.stddev <= limits.angle_deg;
    case Kind::kOffset:
      return p.stddev <= limits.offset;
    case Kind::kTime:
      return p.stddev <= limits.time_offset;
  }
  return false;
}

std::string resultText(const CalibrationResult& r, const TrustLimits& limits) {
  std::ostringstream s;
  s << "estimated from " << r.points << " points and " << r.terms << " planes; median distance off the planes "
    << millimetres(r.median_distance_before) << " before, " << millimetres(r.median_distance_after) << " after\n";
  for (const auto& p : r.parameters) {
    s << "  " << p.name << ": ";
    if (!p.estimated) {
      s << shown(p, p.value) << " held (not observable from a still base: " << p.held_because << ")\n";
    } else if (!trusted(p, limits)) {
      s << "not determined by this recording (standard deviation " << shown(p, p.stddev)
        << "); the rig block keeps the believed " << shown(p, p.believed) << "\n";
    } else {
      s << shown(p, p.value) << " +- " << shown(p, p.stddev, 1) << " (believed " << shown(p, p.believed) << ", change "
        << shown(p, p.value - p.believed) << ")\n";
    }
  }
  return s.str();
}

std::string rigBlock(const CalibrationResult& r, const TrustLimits& limits, const std::string& lidar_model) {
  std::ostringstream s;
  s << "# From `uampc calibrate`: median distance off the map's planes " << millimetres(r.median_distance_after)
    << " over " << r.terms << " planes. Held, not observable from a still base:";
  for (const auto& p : r.parameters)
    if (!p.estimated || !trusted(p, limits)) s << " " << p.name;
  s << " (docs/user/calibration.md).\n";
  s << "rig:\n";
  s << "  lidar_model: " << lidar_model << "\n";
  s << "  lidar_rotation_rpy_deg: [" << number(kept(named(r, "roll_deg"), limits)) << ", "
    << number(kept(named(r, "pitch_deg"), limits)) << ", " << number(kept(named(r, "yaw_deg"), limits)) << "]\n";
  s << "  lidar_offset: [" << number(kept(named(r, "x"), limits)) << ", " << number(kept(named(r, "y"), limits)) << ", "
    << number(kept(named(r, "z"), limits)) << "]\n";
  s << "  encoder_offset_deg: " << number(kept(named(r, "encoder_offset_deg"), limits)) << "\n";
  s << "  time_offset: " << number(kept(named(r, "time_offset"), limits)) << "\n";
  return s.str();
}

std::string thicknessFigure(const CalibrationResult& r) {
  // Histograms of |distance| in 1 mm bins up to the 99th percentile of the "before" distances.
  std::vector<double> before(r.distances_before), after(r.distances_after);
  for (auto& d : before) d = std::abs(d) * 1e3;
  for (auto& d : after) d = std::abs(d) * 1e3;
  std::vector<double> sorted(before);
  std::sort(sorted.begin(), sorted.end());
  const double top = sorted.empty() ? 10.0 : std::max(5.0, sorted[sorted.size() * 99 / 100]);
  const double bin = std::max(0.5, std::round(top / 60.0));
  auto histogram = [&](const std::vector<double>& values, const std::string& label, std::size_t colour) {
    app::svg::Series series;
    series.label = label;
    series.colour = app::svg::paletteColour(colour);
    const std::size_t bins = static_cast<std::size_t>(std::ceil(top / bin));
    std::vector<double> counts(bins, 0.0);
    for (double v : values)
      if (v < top) counts[static_cast<std::size_t>(v / bin)] += 1.0;
    for (std::size_t i = 0; i < bins; ++i) {
      series.x.push_back((static_cast<double>(i) + 0.5) * bin);
      series.y.push_back(values.empty() ? 0.0 : counts[i] / static_cast<double>(values.size()));
    }
    return series;
  };
  app::svg::LinePlot plot;
  plot.title = "The map's points off its planes, before and after calibration";
  plot.x_label = "distance off the plane the other motor angles saw, mm";
  plot.y_label = "fraction of the planes' points";
  plot.series.push_back(histogram(before, "believed rig, median " + millimetres(r.median_distance_before), 0));
  plot.series.push_back(histogram(after, "calibrated, median " + millimetres(r.median_distance_after), 1));
  return app::svg::render(plot);
}

}  // namespace uampc::calibration
