// A small SVG plotting module for the experiment report: line plots and scatter plots with axes,
// ticks and a legend (optionally with equal axis scales over a background of filled cells, for
// top views), heat maps with a colour bar, and box plots with every value drawn as a dot. Output is a standalone SVG
// document whose root carries width and height, so that an <img> gets a natural size.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace uampc::app::svg {

struct Series {
  std::string label;         // empty: not in the legend
  std::vector<double> x, y;  // NaN breaks a line
  std::string colour = "#1f77b4";
  bool points = false;  // markers instead of a line
  double width = 1.5;   // line width or marker radius, px
};

// An axis-aligned rectangle in data coordinates (top-view background).
struct Cell {
  double x0, y0, x1, y1;
  std::string fill;
};

struct LinePlot {
  std::string title, x_label, y_label;
  int width = 760, height = 420;
  bool equal_aspect = false;  // one metre is as long on both axes (top views)
  std::vector<Cell> background;
  std::vector<Series> series;
};
std::string render(const LinePlot& plot);

struct HeatMap {
  std::string title, x_label, y_label, value_label;
  int width = 760, height = 420;
  std::vector<double> x_edges, y_edges;                 // nx + 1 and ny + 1 increasing edges
  std::vector<double> values;                           // ny rows of nx: values[iy * nx + ix]; NaN left blank
  std::vector<std::pair<double, std::string>> y_ticks;  // optional labelled ticks (e.g. in pi)
};
std::string render(const HeatMap& map);

// Tukey's box of a group of values (NaN ignored): quartiles as R's quantile() (type 7), whiskers
// to the most extreme values within 1.5 interquartile ranges of the box.
struct BoxStatistics {
  int count = 0;
  double q1 = 0, median = 0, q3 = 0;
  double whisker_low = 0, whisker_high = 0;
};
BoxStatistics boxStatistics(const std::vector<double>& values);

struct Box {
  std::string label;
  std::vector<double> values;  // a group with no finite value gets its label but no box
  std::vector<bool> marked;    // per value (or empty): drawn as a ring in the marked colour
  std::string colour = "#1f77b4";
};

// One box per group side by side, each value a dot over its box (spread sideways so equal values
// stay visible). The value axis is logarithmic when every value is positive and the largest is
// more than log_above times the smallest: one run that ran away would squash the others flat.
struct BoxPlot {
  std::string title, y_label;
  std::string marked_label;  // legend text of the marked values
  int width = 760, height = 420;
  double log_above = 20.0;
  std::vector<Box> boxes;
};
// True when render() draws plot's value axis logarithmically.
bool usesLogScale(const BoxPlot& plot);
std::string render(const BoxPlot& plot);

// Ticks at 1, 2 or 5 times a power of ten, about `target` of them, covering [lo, hi].
std::vector<double> niceTicks(double lo, double hi, int target);
// Colour of the i-th series (a palette that stays readable for colour-blind readers).
std::string paletteColour(std::size_t index);
// Viridis for t in [0, 1], as #rrggbb.
std::string viridis(double t);
// Text for XML (SVG, the report, DDS Security documents): & < > " ' escaped.
std::string escapeXml(const std::string& text);

}  // namespace uampc::app::svg
