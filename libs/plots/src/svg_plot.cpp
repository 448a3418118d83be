#include "uampc/plots/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "uampc/plots/paired_statistics.hpp"
#include "uampc/colour_map/viridis.hpp"

namespace uampc::app::svg {

namespace {

constexpr double kLeft = 72, kTop = 36, kBottom = 52, kLegendWidth = 170, kRightPlain = 24;

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", v);
  return buffer;
}

std::string tickLabel(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return buffer;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  // An empty or zero-width range still needs an axis.
  void settle() {
    if (lo > hi) lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-12) {
      const double pad = std::max(std::abs(lo) * 0.1, 0.5);
      lo -= pad;
      hi += pad;
    }
  }
  double span() const { return hi - lo; }
};

// Widens a range to whole tick steps, so the frame starts and ends on a labelled tick.
void snapToTicks(Range& r) {
  const auto ticks = niceTicks(r.lo, r.hi, 6);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : r.span();
  r.lo = std::floor(r.lo / step + 1e-9) * step;
  r.hi = std::ceil(r.hi / step - 1e-9) * step;
}

// The plot area in pixels and the mapping from data to it.
struct Frame {
  double x0, y0, w, h;  // pixels, top-left origin
  Range xr, yr;
  double px(double x) const { return x0 + (x - xr.lo) / xr.span() * w; }
  double py(double y) const { return y0 + h - (y - yr.lo) / yr.span() * h; }
};

std::string header(int width, int height, const std::string& title) {
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
       std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
       "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s += "<title>" + escapeXml(title) + "</title>\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + num(width / 2.0) + "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" + escapeXml(title) +
       "</text>\n";
  return s;
}

std::vector<std::pair<double, std::string>> yTicks(const Frame& f,
                                                   const std::vector<std::pair<double, std::string>>& given) {
  if (!given.empty()) return given;
  std::vector<std::pair<double, std::string>> yt;
  const auto ticks = niceTicks(f.yr.lo, f.yr.hi, 6);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  for (double t : ticks) yt.emplace_back(t, tickLabel(t, step));
  return yt;
}

// Grid lines go under the data; frame, ticks and labels over it (axes()).
std::string grid(const Frame& f) {
  std::string s = "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (double t : niceTicks(f.xr.lo, f.xr.hi, 7))
    s += "<line x1=\"" + num(f.px(t)) + "\" y1=\"" + num(f.y0) + "\" x2=\"" + num(f.px(t)) + "\" y2=\"" +
         num(f.y0 + f.h) + "\"/>\n";
  for (const auto& [t, _] : yTicks(f, {}))
    s += "<line x1=\"" + num(f.x0) + "\" y1=\"" + num(f.py(t)) + "\" x2=\"" + num(f.x0 + f.w) + "\" y2=\"" +
         num(f.py(t)) + "\"/>\n";
  return s + "</g>\n";
}

std::string axes(const Frame& f, const std::string& x_label, const std::string& y_label,
                 const std::vector<std::pair<double, std::string>>& y_ticks_override = {}) {
  const auto xt = niceTicks(f.xr.lo, f.xr.hi, 7);
  const auto yt = yTicks(f, y_ticks_override);
  std::string s = "<g stroke=\"#333\" stroke-width=\"1\">\n";
  s += "<rect x=\"" + num(f.x0) + "\" y=\"" + num(f.y0) + "\" width=\"" + num(f.w) + "\" height=\"" + num(f.h) +
       "\" fill=\"none\"/>\n";
  for (double t : xt)
    s += "<line x1=\"" + num(f.px(t)) + "\" y1=\"" + num(f.y0 + f.h) + "\" x2=\"" + num(f.px(t)) + "\" y2=\"" +
         num(f.y0 + f.h + 5) + "\"/>\n";
  for (const auto& [t, _] : yt)
    s += "<line x1=\"" + num(f.x0 - 5) + "\" y1=\"" + num(f.py(t)) + "\" x2=\"" + num(f.x0) + "\" y2=\"" +
         num(f.py(t)) + "\"/>\n";
  s += "</g>\n<g fill=\"#333\">\n";
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  for (double t : xt)
    s += "<text x=\"" + num(f.px(t)) + "\" y=\"" + num(f.y0 + f.h + 18) + "\" text-anchor=\"middle\">" +
         escapeXml(tickLabel(t, xstep)) + "</text>\n";
  for (const auto& [t, label] : yt)
    s += "<text x=\"" + num(f.x0 - 8) + "\" y=\"" + num(f.py(t) + 4) + "\" text-anchor=\"end\">" + escapeXml(label) +
         "</text>\n";
  s += "<text x=\"" + num(f.x0 + f.w / 2) + "\" y=\"" + num(f.y0 + f.h + 40) + "\" text-anchor=\"middle\">" +
       escapeXml(x_label) + "</text>\n";
  s += "<text transform=\"translate(16," + num(f.y0 + f.h / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
       escapeXml(y_label) + "</text>\n</g>\n";
  return s;
}

std::string clipPath(const Frame& f) {
  return "<defs><clipPath id=\"plot-area\"><rect x=\"" + num(f.x0) + "\" y=\"" + num(f.y0) + "\" width=\"" + num(f.w) +
         "\" height=\"" + num(f.h) + "\"/></clipPath></defs>\n";
}

// One polyline per unbroken stretch; points closer than a third of a pixel to the last one kept
// are dropped, so a 200 Hz series over minutes stays a small file.
std::string line(const Frame& f, const Series& s) {
  std::string out, points;
  double last_x = std::numeric_limits<double>::quiet_NaN(), last_y = last_x;
  auto flush = [&] {
    if (!points.empty()) {
      out += "<polyline fill=\"none\" stroke=\"" + s.colour + "\" stroke-width=\"" + num(s.width) +
             "\" stroke-linejoin=\"round\" points=\"" + points + "\"/>\n";
    }
    points.clear();
    last_x = std::numeric_limits<double>::quiet_NaN();
  };
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      flush();
      continue;
    }
    const double x = f.px(s.x[i]), y = f.py(s.y[i]);
    const bool last = i + 1 == std::min(s.x.size(), s.y.size());
    if (std::isfinite(last_x) && std::abs(x - last_x) < 0.33 && std::abs(y - last_y) < 0.33 && !last) continue;
    points += (points.empty() ? "" : " ") + num(x) + "," + num(y);
    last_x = x;
    last_y = y;
  }
  flush();
  return out;
}

std::string markers(const Frame& f, const Series& s) {
  std::string out = "<g fill=\"" + s.colour + "\" fill-opacity=\"0.85\">\n";
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
    out += "<circle cx=\"" + num(f.px(s.x[i])) + "\" cy=\"" + num(f.py(s.y[i])) + "\" r=\"" + num(s.width) + "\"/>\n";
  }
  return out + "</g>\n";
}

std::string legend(const std::vector<Series>& series, double x, double y) {
  std::string s = "<g>\n";
  for (const Series& item : series) {
    if (item.label.empty()) continue;
    if (item.points) {
      s += "<circle cx=\"" + num(x + 11) + "\" cy=\"" + num(y - 4) + "\" r=\"4\" fill=\"" + item.colour + "\"/>\n";
    } else {
      s += "<line x1=\"" + num(x) + "\" y1=\"" + num(y - 4) + "\" x2=\"" + num(x + 22) + "\" y2=\"" + num(y - 4) +
           "\" stroke=\"" + item.colour + "\" stroke-width=\"3\"/>\n";
    }
    s += "<text x=\"" + num(x + 28) + "\" y=\"" + num(y) + "\">" + escapeXml(item.label) + "</text>\n";
    y += 18;
  }
  return s + "</g>\n";
}

// Frame, value ticks and labels of a plot whose x axis is categories (box plots): each category's
// label under its position.
std::string categoryAxes(const Frame& f, const std::vector<std::pair<double, std::string>>& categories,
                         const std::vector<std::pair<double, std::string>>& y_ticks, const std::string& y_label) {
  std::string s = "<g stroke=\"#333\" stroke-width=\"1\">\n<rect x=\"" + num(f.x0) + "\" y=\"" + num(f.y0) +
                  "\" width=\"" + num(f.w) + "\" height=\"" + num(f.h) + "\" fill=\"none\"/>\n";
  for (const auto& [t, _] : y_ticks)
    s += "<line x1=\"" + num(f.x0 - 5) + "\" y1=\"" + num(f.py(t)) + "\" x2=\"" + num(f.x0) + "\" y2=\"" +
         num(f.py(t)) + "\"/>\n";
  s += "</g>\n<g fill=\"#333\">\n";
  for (const auto& [x, label] : categories)
    s += "<text x=\"" + num(f.px(x)) + "\" y=\"" + num(f.y0 + f.h + 18) + "\" text-anchor=\"middle\">" +
         escapeXml(label) + "</text>\n";
  for (const auto& [t, label] : y_ticks)
    s += "<text x=\"" + num(f.x0 - 8) + "\" y=\"" + num(f.py(t) + 4) + "\" text-anchor=\"end\">" + escapeXml(label) +
         "</text>\n";
  s += "<text transform=\"translate(16," + num(f.y0 + f.h / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
       escapeXml(y_label) + "</text>\n</g>\n";
  return s;
}

// Ticks of a logarithmic axis over [lo, hi] in log10 units (whole decades): every power of ten,
// and 2 and 5 times it when the axis spans at most three decades. Labels in the values' units.
std::vector<std::pair<double, std::string>> logTicks(double lo, double hi) {
  std::vector<std::pair<double, std::string>> ticks;
  const bool dense = hi - lo <= 3;
  for (int decade = static_cast<int>(lo); decade <= static_cast<int>(hi); ++decade) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m > 1 && !dense) continue;
      const double at = decade + std::log10(m);
      if (at > hi + 1e-9) break;
      char label[32];
      std::snprintf(label, sizeof(label), "%g", m * std::pow(10.0, decade));
      ticks.emplace_back(at, label);
    }
  }
  return ticks;
}

// The golden-ratio sequence spreads the k-th dot of a box sideways in [-0.5, 0.5), evenly and the
// same way every time (no random jitter: the figure is reproducible).
double spread(std::size_t k) {
  const double x = static_cast<double>(k) * 0.6180339887498949;
  return x - std::floor(x) - 0.5;
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power * 10;
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  }
  std::vector<double> ticks;
  // Multiples of the step by index, not by repeated addition, so errors do not accumulate.
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k += 1) ticks.push_back(k * step + 0.0);
  return ticks;
}

std::string paletteColour(std::size_t index) {
  // Okabe-Ito, without its yellow (too pale on white).
  static const std::array<const char*, 7> kColours{"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                   "#E69F00", "#56B4E9", "#000000"};
  return kColours[index % kColours.size()];
}

std::string viridis(double t) {
  const auto rgb = colour_map::viridis(t);
  char buffer[8];
  std::snprintf(buffer, sizeof(buffer), "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return buffer;
}

std::string escapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string render(const LinePlot& plot) {
  bool any_label = false;
  Range xr, yr;
  for (const Series& s : plot.series) {
    any_label = any_label || !s.label.empty();
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) xr.add(s.x[i]), yr.add(s.y[i]);
    }
  }
  for (const Cell& c : plot.background) xr.add(c.x0), xr.add(c.x1), yr.add(c.y0), yr.add(c.y1);
  xr.settle();
  yr.settle();
  Frame f{kLeft, kTop, plot.width - kLeft - (any_label ? kLegendWidth : kRightPlain), plot.height - kTop - kBottom,
          xr,    yr};
  if (plot.equal_aspect) {
    // Widen the narrower axis about its centre so one metre takes as many pixels either way.
    const double scale = std::min(f.w / xr.span(), f.h / yr.span());
    const double xc = (xr.lo + xr.hi) / 2, yc = (yr.lo + yr.hi) / 2;
    f.xr = {xc - f.w / scale / 2, xc + f.w / scale / 2};
    f.yr = {yc - f.h / scale / 2, yc + f.h / scale / 2};
  } else {
    snapToTicks(f.xr);
    snapToTicks(f.yr);
  }
  std::string s =
      header(plot.width, plot.height, plot.title) + clipPath(f) + grid(f) + "<g clip-path=\"url(#plot-area)\">\n";
  for (const Cell& c : plot.background) {
    const double x = f.px(c.x0), y = f.py(c.y1);
    s += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(f.px(c.x1) - x) + "\" height=\"" +
         num(f.py(c.y0) - y) + "\" fill=\"" + c.fill + "\"/>\n";
  }
  for (const Series& series : plot.series) s += series.points ? markers(f, series) : line(f, series);
  s += "</g>\n" + axes(f, plot.x_label, plot.y_label);
  if (any_label) s += legend(plot.series, f.x0 + f.w + 14, f.y0 + 12);
  return s + "</svg>\n";
}

std::string render(const HeatMap& map) {
  const std::size_t nx = map.x_edges.size() > 1 ? map.x_edges.size() - 1 : 0;
  const std::size_t ny = map.y_edges.size() > 1 ? map.y_edges.size() - 1 : 0;
  Range xr, yr, vr;
  if (nx && ny) xr = {map.x_edges.front(), map.x_edges.back()}, yr = {map.y_edges.front(), map.y_edges.back()};
  for (std::size_t i = 0; i < std::min(map.values.size(), nx * ny); ++i) vr.add(map.values[i]);
  xr.settle();
  yr.settle();
  vr.settle();
  const Frame f{kLeft, kTop, map.width - kLeft - 110.0, map.height - kTop - kBottom, xr, yr};
  std::string s = header(map.width, map.height, map.title) + clipPath(f) + "<g clip-path=\"url(#plot-area)\">\n";
  // Colours are quantised to 64 levels and equal neighbours in a row merged into one rectangle:
  // the file shrinks several times and the eye cannot tell.
  auto level = [&](double v) { return std::lround((v - vr.lo) / vr.span() * 63.0); };
  for (std::size_t iy = 0; iy < ny; ++iy) {
    const double top = f.py(map.y_edges[iy + 1]), bottom = f.py(map.y_edges[iy]);
    for (std::size_t ix = 0; ix < nx;) {
      const double v = map.values[iy * nx + ix];
      std::size_t end = ix + 1;
      if (std::isfinite(v)) {
        while (end < nx && std::isfinite(map.values[iy * nx + end]) && level(map.values[iy * nx + end]) == level(v))
          ++end;
        const double left = f.px(map.x_edges[ix]), right = f.px(map.x_edges[end]);
        // A quarter-pixel overlap hides the hairline seams browsers draw between abutting cells.
        s += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(right - left + 0.25) +
             "\" height=\"" + num(bottom - top + 0.25) + "\" fill=\"" + viridis(level(v) / 63.0) + "\"/>\n";
      }
      ix = end;
    }
  }
  s += "</g>\n" + axes(f, map.x_label, map.y_label, map.y_ticks);
  // Colour bar.
  const double bx = f.x0 + f.w + 18, bw = 16;
  Frame bar{bx, f.y0, bw, f.h, {0, 1}, vr};
  s += "<g>\n";
  for (int k = 0; k < 64; ++k) {
    const double y0 = f.y0 + f.h * (1.0 - (k + 1) / 64.0);
    s += "<rect x=\"" + num(bx) + "\" y=\"" + num(y0) + "\" width=\"" + num(bw) + "\" height=\"" +
         num(f.h / 64.0 + 0.25) + "\" fill=\"" + viridis(k / 63.0) + "\"/>\n";
  }
  const auto ticks = niceTicks(vr.lo, vr.hi, 5);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  for (double t : ticks) {
    s += "<line x1=\"" + num(bx + bw) + "\" y1=\"" + num(bar.py(t)) + "\" x2=\"" + num(bx + bw + 4) + "\" y2=\"" +
         num(bar.py(t)) + "\" stroke=\"#333\"/>\n<text x=\"" + num(bx + bw + 7) + "\" y=\"" + num(bar.py(t) + 4) +
         "\" fill=\"#333\">" + escapeXml(tickLabel(t, step)) + "</text>\n";
  }
  s += "<text transform=\"translate(" + num(map.width - 10.0) + "," + num(f.y0 + f.h / 2) +
       ") rotate(-90)\" text-anchor=\"middle\" fill=\"#333\">" + escapeXml(map.value_label) + "</text>\n</g>\n";
  return s + "</svg>\n";
}

}  // namespace uampc::app::svg

namespace uampc::app::svg {

BoxStatistics boxStatistics(const std::vector<double>& values) {
  std::vector<double> finite;
  for (double v : values) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  BoxStatistics b;
  b.count = static_cast<int>(finite.size());
  if (finite.empty()) return b;
  b.q1 = quantile(finite, 0.25);
  b.median = median(finite);
  b.q3 = quantile(finite, 0.75);
  const double reach = 1.5 * (b.q3 - b.q1);
  b.whisker_low = std::numeric_limits<double>::infinity();
  b.whisker_high = -b.whisker_low;
  for (double v : finite) {
    if (v >= b.q1 - reach) b.whisker_low = std::min(b.whisker_low, v);
    if (v <= b.q3 + reach) b.whisker_high = std::max(b.whisker_high, v);
  }
  return b;
}

bool usesLogScale(const BoxPlot& plot) {
  Range r;
  for (const Box& box : plot.boxes) {
    for (double v : box.values) {
      if (!std::isfinite(v)) continue;
      if (v <= 0) return false;
      r.add(v);
    }
  }
  return r.lo <= r.hi && r.hi > plot.log_above * r.lo;
}

std::string render(const BoxPlot& plot) {
  const bool log = usesLogScale(plot);
  auto axis = [log](double v) { return log ? std::log10(v) : v; };
  bool any_marked = false;
  Range yr;
  for (const Box& box : plot.boxes) {
    for (std::size_t k = 0; k < box.values.size(); ++k) {
      if (!std::isfinite(box.values[k])) continue;
      yr.add(axis(box.values[k]));
      any_marked = any_marked || (k < box.marked.size() && box.marked[k]);
    }
  }
  if (!log && yr.lo <= yr.hi && yr.lo > 0) yr.add(0);  // errors: from zero, so heights compare
  yr.settle();
  if (log) {
    yr.lo = std::floor(yr.lo);
    yr.hi = std::max(std::ceil(yr.hi), yr.lo + 1);
  } else {
    snapToTicks(yr);
  }
  const bool legend_shown = any_marked && !plot.marked_label.empty();
  const double n = std::max<double>(1, plot.boxes.size());
  const Frame f{
      kLeft,       kTop, plot.width - kLeft - (legend_shown ? kLegendWidth : kRightPlain), plot.height - kTop - kBottom,
      Range{0, n}, yr};
  const auto y_ticks = log ? logTicks(yr.lo, yr.hi) : yTicks(f, {});
  std::string s = header(plot.width, plot.height, plot.title) + "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (const auto& [t, _] : y_ticks)
    s += "<line x1=\"" + num(f.x0) + "\" y1=\"" + num(f.py(t)) + "\" x2=\"" + num(f.x0 + f.w) + "\" y2=\"" +
         num(f.py(t)) + "\"/>\n";
  s += "</g>\n";
  const double half = std::min(30.0, f.w / n * 0.3);  // half a box's width, px
  const char* const kMarked = "#b00000";
  std::vector<std::pair<double, std::string>> categories;
  for (std::size_t i = 0; i < plot.boxes.size(); ++i) {
    const Box& box = plot.boxes[i];
    const double cx = f.px(i + 0.5);
    categories.emplace_back(i + 0.5, box.label);
    const BoxStatistics b = boxStatistics(box.values);
    if (b.count == 0) continue;
    auto hline = [&](double value, double w, const std::string& extra) {
      return "<line x1=\"" + num(cx - w) + "\" y1=\"" + num(f.py(axis(value))) + "\" x2=\"" + num(cx + w) + "\" y2=\"" +
             num(f.py(axis(value))) + "\"" + extra + "/>\n";
    };
    auto vline = [&](double from, double to) {
      return "<line x1=\"" + num(cx) + "\" y1=\"" + num(f.py(axis(from))) + "\" x2=\"" + num(cx) + "\" y2=\"" +
             num(f.py(axis(to))) + "\"/>\n";
    };
    s += "<g class=\"box\" stroke=\"" + box.colour + "\" stroke-width=\"1.5\">\n";
    s += vline(b.whisker_low, b.q1) + vline(b.q3, b.whisker_high) + hline(b.whisker_low, half / 2, "") +
         hline(b.whisker_high, half / 2, "");
    const double top = f.py(axis(b.q3)), bottom = f.py(axis(b.q1));
    s += "<rect x=\"" + num(cx - half) + "\" y=\"" + num(top) + "\" width=\"" + num(2 * half) + "\" height=\"" +
         num(bottom - top) + "\" fill=\"" + box.colour + "\" fill-opacity=\"0.15\"/>\n";
    s += hline(b.median, half, " class=\"median\" stroke-width=\"3\"") + "</g>\n<g fill=\"" + box.colour + "\">\n";
    for (std::size_t k = 0; k < box.values.size(); ++k) {
      if (!std::isfinite(box.values[k])) continue;
      const std::string at =
          "cx=\"" + num(cx + spread(k) * half * 1.4) + "\" cy=\"" + num(f.py(axis(box.values[k]))) + "\"";
      if (k < box.marked.size() && box.marked[k]) {
        s += "<circle class=\"marked\" " + at + " r=\"5\" fill=\"white\" fill-opacity=\"0.6\" stroke=\"" + kMarked +
             "\" stroke-width=\"2\"/>\n";
      } else {
        s += "<circle class=\"value\" " + at + " r=\"3.5\" fill-opacity=\"0.85\"/>\n";
      }
    }
    s += "</g>\n";
  }
  s += categoryAxes(f, categories, y_ticks, plot.y_label + (log ? " (log scale)" : ""));
  if (legend_shown) {
    const double x = f.x0 + f.w + 14, y = f.y0 + 12;
    s += "<circle cx=\"" + num(x + 11) + "\" cy=\"" + num(y - 4) + "\" r=\"5\" fill=\"white\" stroke=\"" + kMarked +
         "\" stroke-width=\"2\"/>\n<text x=\"" + num(x + 28) + "\" y=\"" + num(y) + "\">" +
         escapeXml(plot.marked_label) + "</text>\n";
  }
  return s + "</svg>\n";
}

}  // namespace uampc::app::svg
