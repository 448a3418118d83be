// The SVG writer: documents are well-formed XML (a small checker here, and xmllint when the
// machine has it), carry width and height, escape text, and place data where the axes say.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "command_runner.hpp"
#include "uampc/plots/svg_plot.hpp"
#include "uampc/run_files/text_file.hpp"

namespace uampc::app::svg {
namespace {

// Well-formedness, enough for what the writer emits: one root, balanced and properly nested
// elements, quoted attributes without raw '<' or '&', known entities in text. Returns "" if fine.
std::string checkXml(const std::string& xml) {
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = 0;
  auto entityOk = [&](std::size_t at) {
    static const std::regex kEntity("&(amp|lt|gt|quot|apos|#[0-9]+|#x[0-9a-fA-F]+);");
    std::smatch m;
    const std::string rest = xml.substr(at, 12);
    return std::regex_search(rest, m, kEntity) && m.position() == 0;
  };
  while (i < xml.size()) {
    if (xml[i] == '&' && !entityOk(i)) return "bad entity at " + std::to_string(i);
    if (xml[i] != '<') {
      if (open.empty() && !std::isspace(static_cast<unsigned char>(xml[i]))) return "text outside the root";
      ++i;
      continue;
    }
    if (xml.compare(i, 5, "<?xml") == 0) {
      i = xml.find("?>", i);
      if (i == std::string::npos) return "unclosed declaration";
      i += 2;
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      i = xml.find("-->", i);
      if (i == std::string::npos) return "unclosed comment";
      i += 3;
      continue;
    }
    const bool closing = xml[i + 1] == '/';
    std::size_t j = i + (closing ? 2 : 1);
    std::size_t name_end = j;
    while (name_end < xml.size() && (std::isalnum(static_cast<unsigned char>(xml[name_end])) || xml[name_end] == '-' ||
                                     xml[name_end] == ':' || xml[name_end] == '_'))
      ++name_end;
    const std::string name = xml.substr(j, name_end - j);
    if (name.empty()) return "tag without a name at " + std::to_string(i);
    // Attributes: name="value" pairs up to > or />.
    std::size_t k = name_end;
    static const std::regex kAttribute(R"(^\s+[A-Za-z_:][-A-Za-z0-9_:.]*="[^"<]*")");
    while (true) {
      std::smatch m;
      const std::string rest = xml.substr(k, 4096);
      if (std::regex_search(rest, m, kAttribute)) {
        for (std::size_t a = k; a < k + m.length(); ++a) {
          if (xml[a] == '&' && !entityOk(a)) return "bad entity in an attribute of <" + name + ">";
        }
        k += m.length();
        continue;
      }
      break;
    }
    while (k < xml.size() && std::isspace(static_cast<unsigned char>(xml[k]))) ++k;
    const bool self_closing = xml.compare(k, 2, "/>") == 0;
    if (!self_closing && xml[k] != '>') return "malformed tag <" + name + "> at " + std::to_string(i);
    i = k + (self_closing ? 2 : 1);
    if (closing) {
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " + (open.empty() ? "nothing" : "<" + open.back() + ">");
      open.pop_back();
    } else {
      if (open.empty() && ++roots > 1) return "more than one root element";
      if (!self_closing) open.push_back(name);
    }
  }
  if (!open.empty()) return "<" + open.back() + "> not closed";
  return roots == 1 ? "" : "no root element";
}

void expectWellFormed(const std::string& svg_text, const std::string& name) {
  EXPECT_EQ(checkXml(svg_text), "") << name;
  EXPECT_TRUE(std::regex_search(svg_text, std::regex("<svg [^>]*width=\"[0-9]+\" height=\"[0-9]+\""))) << name;
  if (std::filesystem::exists("/usr/bin/xmllint")) {
    const std::string path = test::freshDirectory("svg_plot_test_" + name) + "/figure.svg";
    run_files::writeTextFile(path, svg_text);
    const auto r = test::runShell("/usr/bin/xmllint --noout " + path);
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
}

TEST(XmlChecker, CatchesWhatItShould) {
  EXPECT_EQ(checkXml("<a x=\"1\"><b/></a>"), "");
  EXPECT_NE(checkXml("<a><b></a></b>"), "");
  EXPECT_NE(checkXml("<a>x & y</a>"), "");
  EXPECT_NE(checkXml("<a x=1></a>"), "");
  EXPECT_NE(checkXml("<a></a><b/>"), "");
  EXPECT_NE(checkXml("<a>"), "");
}

TEST(SvgPlot, LinePlotIsWellFormedAndEscapesText) {
  LinePlot plot;
  plot.title = "ATE <over> time & \"more\"";
  plot.x_label = "t, s";
  plot.y_label = "error, m";
  plot.series.push_back({"ua_mpc & co", {0, 1, 2, NAN, 4, 5}, {0, 1, 4, 9, 16, 25}, paletteColour(0), false, 1.5});
  plot.series.push_back({"points", {1, 2}, {3, 4}, paletteColour(1), true, 4});
  plot.background.push_back({0, 0, 1, 1, "#cccccc"});
  const std::string text = render(plot);
  expectWellFormed(text, "line");
  EXPECT_NE(text.find("ATE &lt;over&gt; time &amp; &quot;more&quot;"), std::string::npos);
  EXPECT_NE(text.find("ua_mpc &amp; co"), std::string::npos);
  // The NaN breaks the line in two.
  std::size_t polylines = 0;
  for (std::size_t at = text.find("<polyline"); at != std::string::npos; at = text.find("<polyline", at + 1))
    ++polylines;
  EXPECT_EQ(polylines, 2u);
}

TEST(SvgPlot, EmptyAndDegenerateDataStillGiveAnAxis) {
  LinePlot empty;
  expectWellFormed(render(empty), "empty");
  LinePlot flat;
  flat.series.push_back({"flat", {0, 1, 2}, {3, 3, 3}, "#000", false, 1});
  flat.equal_aspect = true;
  expectWellFormed(render(flat), "flat");
}

TEST(SvgPlot, HeatMapIsWellFormedWithAColourBar) {
  HeatMap map;
  map.title = "U";
  map.x_edges = {0, 1, 2, 3};
  map.y_edges = {0, M_PI, 2 * M_PI};
  map.values = {1, 2, 3, 4, NAN, 6};
  map.y_ticks = {{0, "0"}, {M_PI, "\xcf\x80"}, {2 * M_PI, "2\xcf\x80"}};
  const std::string text = render(map);
  expectWellFormed(text, "heat");
  EXPECT_NE(text.find(viridis(0.0)), std::string::npos);  // the lowest value and the bar's bottom
  EXPECT_NE(text.find(viridis(1.0)), std::string::npos);
  EXPECT_NE(text.find(">2\xcf\x80<"), std::string::npos);
}

std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SvgPlot, BoxStatisticsAreTukeysBox) {
  // R: quantile(c(1, 2, 3, 4, 100)) gives 2, 3, 4 for the quartiles; the upper fence is
  // 4 + 1.5 * 2 = 7, so the whisker stops at 4 and 100 is beyond it; nothing is below 2 - 3.
  const BoxStatistics b = boxStatistics({100, 3, 1, NAN, 4, 2});
  EXPECT_EQ(b.count, 5);
  EXPECT_DOUBLE_EQ(b.q1, 2);
  EXPECT_DOUBLE_EQ(b.median, 3);
  EXPECT_DOUBLE_EQ(b.q3, 4);
  EXPECT_DOUBLE_EQ(b.whisker_low, 1);
  EXPECT_DOUBLE_EQ(b.whisker_high, 4);
  EXPECT_EQ(boxStatistics({NAN}).count, 0);
}

TEST(SvgPlot, BoxPlotDrawsABoxPerGroupEveryValueAndTheMarkedOnes) {
  BoxPlot plot;
  plot.title = "ATE";
  plot.y_label = "ATE, m";
  plot.marked_label = "lost track";
  plot.boxes.push_back({"a & b", {1, 2, 3}, {false, false, true}, paletteColour(0)});
  plot.boxes.push_back({"empty", {}, {}, paletteColour(1)});  // label, no box
  plot.boxes.push_back({"c", {4, 5, 6, 7}, {}, paletteColour(2)});
  EXPECT_FALSE(usesLogScale(plot));  // 7 / 1 < 20
  const std::string text = render(plot);
  expectWellFormed(text, "box");
  EXPECT_EQ(countOf(text, "class=\"box\""), 2u);
  EXPECT_EQ(countOf(text, "class=\"median\""), 2u);
  EXPECT_EQ(countOf(text, "class=\"value\""), 6u);
  EXPECT_EQ(countOf(text, "class=\"marked\""), 1u);
  EXPECT_NE(text.find(">a &amp; b<"), std::string::npos);
  EXPECT_NE(text.find(">empty<"), std::string::npos);
  EXPECT_NE(text.find(">lost track<"), std::string::npos);
  EXPECT_EQ(text.find("log scale"), std::string::npos);
  EXPECT_NE(text.find(">0<"), std::string::npos);  // a linear axis from zero
}

TEST(SvgPlot, BoxPlotGoesLogarithmicBeyondAFactorTwenty) {
  BoxPlot plot;
  plot.y_label = "ATE, m";
  plot.boxes.push_back({"held", {0.5, 0.6, 0.7}, {}, paletteColour(0)});
  plot.boxes.push_back({"ran away", {0.8, 40}, {false, true}, paletteColour(1)});
  EXPECT_TRUE(usesLogScale(plot));  // 40 / 0.5 = 80
  const std::string text = render(plot);
  expectWellFormed(text, "log_box");
  EXPECT_NE(text.find("ATE, m (log scale)"), std::string::npos);
  // Whole decades 0.1 .. 100, with 2 and 5 between.
  for (const char* tick : {">0.1<", ">0.2<", ">1<", ">5<", ">100<"})
    EXPECT_NE(text.find(tick), std::string::npos) << tick;
  plot.boxes.push_back({"zero", {0.0}, {}, paletteColour(2)});
  EXPECT_FALSE(usesLogScale(plot));  // a zero has no logarithm
  plot.boxes.back().values = {10.0};
  plot.log_above = 100;
  EXPECT_FALSE(usesLogScale(plot));
}

TEST(SvgPlot, NiceTicks) {
  EXPECT_EQ(niceTicks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const std::vector<double> expected{-0.3, -0.2, -0.1, 0, 0.1, 0.2, 0.3};
  const auto small = niceTicks(-0.3, 0.3, 6);
  ASSERT_EQ(small.size(), expected.size());
  for (std::size_t i = 0; i < small.size(); ++i) EXPECT_NEAR(small[i], expected[i], 1e-12);
  const auto t = niceTicks(3, 980, 5);
  EXPECT_EQ(t.front(), 200);
  EXPECT_EQ(t.back(), 800);
  EXPECT_EQ(viridis(0), "#440154");
  EXPECT_EQ(viridis(1), "#fde725");
}

}  // namespace
}  // namespace uampc::app::svg
