// The report built from hand-made run directories, opened in headless Chromium: every figure
// must load (the page's own script counts <img> elements that decoded into #figure-check).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "command_runner.hpp"
#include "report/test/fake_runs.hpp"
#include "report/report_page.hpp"

namespace uampc::app {
namespace {

constexpr const char* kChromium = "/usr/bin/chromium";

TEST(ReportPage, WritesEveryFigureAndNotesWhatIsMissing) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("report_page_test"));
  const ReportSummary summary =
      writeReport(fake.experiment, fake.results, summarize(fake.experiment, fake.results), fake.directory);
  // Per scene: ATE per run (box plot), ATE over time, motor speed, top view, U(theta), ATE against
  // CMPLT, and four of the six panorama snapshots of the ua_mpc run.
  EXPECT_EQ(summary.figures, 20);
  const std::string html = test::readFile(fake.directory + "/report/index.html");
  std::size_t images = 0;
  const std::regex image("<img src=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), image); it != std::sregex_iterator(); ++it) {
    ++images;
    EXPECT_TRUE(std::filesystem::is_regular_file(fake.directory + "/report/" + (*it)[1].str())) << (*it)[1];
  }
  EXPECT_EQ(images, 20u);
  EXPECT_NE(html.find("<td>1.50</td><td>105</td>"), std::string::npos);  // the summary table
  // The pooled paired comparison, as in results.md.
  EXPECT_NE(html.find("<tr class=\"pooled\"><td>constant_3.6</td><td>all scenes</td><td>4</td><td>0.28</td>"),
            std::string::npos);
  // Evenly spread: the first, two in between and the last snapshot.
  for (const char* shown : {"alpha_panorama_00000.0.png", "alpha_panorama_00001.5.png", "alpha_panorama_00004.5.png",
                            "alpha_panorama_00007.5.png"}) {
    EXPECT_NE(html.find(std::string("src=\"") + shown), std::string::npos) << shown;
  }
  EXPECT_NE(html.find("id=\"figure-check\""), std::string::npos);
}

TEST(ReportPage, BoxPlotOfEveryRunsAtePerScene) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("report_page_boxes_test"));
  writeReport(fake.experiment, fake.results, summarize(fake.experiment, fake.results), fake.directory);
  const std::string html = test::readFile(fake.directory + "/report/index.html");
  for (const char* scene : {"alpha", "beta"}) {
    const std::string file = std::string(scene) + "_ate_boxes.svg";
    EXPECT_NE(html.find("src=\"" + file + "\""), std::string::npos) << file;
    const std::string svg = test::readFile(fake.directory + "/report/" + file);
    auto count = [&svg](const std::string& what) {
      std::size_t n = 0;
      for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
      return n;
    };
    // One box per controller. alpha: 6 runs, zero's two lost; beta: 5 finished (zero's seed 2
    // failed), constant_3.6's seed 2 lost.
    EXPECT_EQ(count("class=\"box\""), 3u) << file;
    const bool alpha = std::string(scene) == "alpha";
    EXPECT_EQ(count("class=\"value\"") + count("class=\"marked\""), alpha ? 6u : 5u) << file;
    EXPECT_EQ(count("class=\"marked\""), alpha ? 2u : 1u) << file;
    EXPECT_EQ(svg.find("log scale"), std::string::npos) << file;  // 1..9 and 3..29.5: within a factor 20
  }
}

TEST(ReportPage, EveryFigureLoadsInHeadlessChromium) {
  if (!std::filesystem::exists(kChromium)) GTEST_SKIP() << kChromium << " is missing (apt-get install chromium)";
  const std::string dir = test::freshDirectory("report_page_chromium_test");
  const auto fake = test::makeFakeExperiment(dir);
  const ReportSummary summary =
      writeReport(fake.experiment, fake.results, summarize(fake.experiment, fake.results), fake.directory);
  ASSERT_EQ(summary.figures, 20);
  const std::string profile = dir + "/chromium_profile";  // fresh: nothing cached from another run
  std::filesystem::create_directories(profile);
  const auto r = test::runShell(std::string("timeout 120 ") + kChromium +
                                " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
                                " --disable-background-networking --disable-component-update --disable-sync"
                                " --user-data-dir=" +
                                profile + " --virtual-time-budget=5000 --dump-dom file://" + fake.directory +
                                "/report/index.html 2>/dev/null");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex(R"(figures loaded: (\d+) of (\d+))"))) << r.output;
  EXPECT_EQ(m[1].str(), "20") << m[0];
  EXPECT_EQ(m[2].str(), "20") << m[0];
}

}  // namespace
}  // namespace uampc::app
