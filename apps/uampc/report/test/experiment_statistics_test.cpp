// The experiment's statistics from hand-made run directories (fake_runs.cpp lists their figures):
// per scene and controller, and ua_mpc paired by scene and seed with every other controller.
#include "report/experiment_statistics.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "command_runner.hpp"
#include "report/test/fake_runs.hpp"
#include "report/results_table.hpp"

namespace uampc::app {
namespace {

TEST(ExperimentStatistics, PerSceneAndController) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("statistics_cells_test"));
  const ExperimentStatistics st = computeStatistics(fake.experiment, fake.results);
  ASSERT_EQ(st.controllers, (std::vector<std::string>{"ua_mpc", "constant_3.6", "zero"}));
  const CellStatistics& ua_alpha = st.cells[0][0];  // ATE 1 and 2 over 50 m: 2% and 4%
  EXPECT_EQ(ua_alpha.runs, 2);
  EXPECT_EQ(ua_alpha.held, 2);
  EXPECT_DOUBLE_EQ(ua_alpha.median_ate_m, 1.5);
  EXPECT_DOUBLE_EQ(ua_alpha.median_ate_percent, 3.0);
  EXPECT_DOUBLE_EQ(ua_alpha.median_cmplt, 105);
  const CellStatistics& constant_beta = st.cells[1][1];  // ATE 10 and 20 over 200 m, seed 2 lost
  EXPECT_EQ(constant_beta.held, 1);
  EXPECT_EQ(constant_beta.lost, 1);
  EXPECT_DOUBLE_EQ(constant_beta.mean_ate_m, 15);
  EXPECT_DOUBLE_EQ(constant_beta.median_ate_percent, 7.5);
  const CellStatistics& zero_alpha = st.cells[2][0];  // both lost, no CMPLT
  EXPECT_EQ(zero_alpha.lost, 2);
  EXPECT_EQ(zero_alpha.held, 0);
  EXPECT_TRUE(std::isnan(zero_alpha.median_cmplt));
  EXPECT_EQ(st.cells[2][1].runs, 1);  // zero/beta/seed 2 failed: not a run of the statistics
  EXPECT_DOUBLE_EQ(st.cells[2][1].median_ate_percent, 14.75);
}

TEST(ExperimentStatistics, PairsByScenePooledOverScenes) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("statistics_pairs_test"));
  const ExperimentStatistics st = computeStatistics(fake.experiment, fake.results);
  ASSERT_EQ(st.subject, "ua_mpc");
  ASSERT_EQ(st.comparisons.size(), 2u);
  // ua_mpc against constant_3.6: (1, 4), (2, 6) in alpha, (3, 10), (4, 20) in beta.
  const BaselineComparison& constant = st.comparisons[0];
  EXPECT_EQ(constant.controller, "constant_3.6");
  EXPECT_EQ(constant.per_scene[0].pairs, 2);
  EXPECT_DOUBLE_EQ(constant.per_scene[0].summed_ate_ratio, 0.3);
  EXPECT_DOUBLE_EQ(constant.per_scene[0].wilcoxon.p_value, 0.5);  // 2 pairs: 2/2^2 at best
  const PairedComparison& pooled = constant.pooled;
  EXPECT_EQ(pooled.pairs, 4);
  EXPECT_DOUBLE_EQ(pooled.median_ate_ratio, (0.25 + 0.3) / 2);  // ratios 0.2, 0.25, 0.3, 0.33
  EXPECT_DOUBLE_EQ(pooled.summed_ate_ratio, 10.0 / 40);
  EXPECT_DOUBLE_EQ(pooled.fraction_subject_lower, 1.0);
  EXPECT_EQ(pooled.subject_lost, 0);
  EXPECT_EQ(pooled.baseline_lost, 1);
  EXPECT_DOUBLE_EQ(pooled.median_cmplt_ratio, 1.05);  // 100/100, 110/100, 50/40, 50/60
  EXPECT_TRUE(pooled.wilcoxon.exact);
  EXPECT_DOUBLE_EQ(pooled.wilcoxon.p_value, 2.0 / 16);  // 4 pairs, all lower
  // Against zero, beta's seed 2 has no pair (zero failed there): 3 pairs, differences -7, -7,
  // -26.5. The tie makes it the normal approximation: W+ = 0, mean 3, variance
  // 3*4*7/24 - (2^3 - 2)/48 = 3.375, z = (3 - 0.5) / sqrt(3.375), p = 0.173568.
  const PairedComparison& zero = st.comparisons[1].pooled;
  EXPECT_EQ(zero.pairs, 3);
  EXPECT_EQ(zero.baseline_lost, 2);
  EXPECT_DOUBLE_EQ(zero.median_ate_ratio, 1.0 / 8);  // 1/8, 2/9, 3/29.5
  EXPECT_FALSE(zero.wilcoxon.exact);
  EXPECT_NEAR(zero.wilcoxon.p_value, 0.1735682, 1e-6);
}

TEST(ExperimentStatistics, ResultsMarkdownShowsThePooledLine) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("statistics_md_test"));
  const std::string md = renderMarkdown(fake.experiment, summarize(fake.experiment, fake.results), fake.results);
  EXPECT_NE(md.find("| alpha | zero | 2 | 0 | 2 | 8.50 | 8.50 | 17.00 | n/a |"), std::string::npos) << md;
  EXPECT_NE(md.find("| constant_3.6 | **all scenes** | 4 | 0.28 | 0.25 | 4/4 (100%) | 0 | 1 | 1.05 | 0.125 | exact, "
                    "n=4 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| zero | **all scenes** | 3 | 0.12 | 0.13 | 3/3 (100%) | 0 | 2 | 2.50 | 0.174 | normal approx., "
                    "n=3 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("0.0625 with 5 pairs"), std::string::npos) << md;
}

TEST(ExperimentStatistics, ResultsJsonCarriesTheSameFigures) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("statistics_json_test"));
  const std::string path = fake.directory + "/results.json";
  writeResultsJson(path, fake.experiment, fake.results);
  const YAML::Node root = YAML::LoadFile(path);
  const YAML::Node st = root["statistics"];
  ASSERT_TRUE(st.IsMap());
  EXPECT_EQ(st["subject"].as<std::string>(), "ua_mpc");
  EXPECT_EQ(st["per_scene"]["beta"]["constant_3.6"]["lost"].as<int>(), 1);
  EXPECT_DOUBLE_EQ(st["per_scene"]["alpha"]["ua_mpc"]["median_ate_percent_of_distance"].as<double>(), 3.0);
  const YAML::Node pooled = st["paired"]["constant_3.6"]["pooled"];
  EXPECT_EQ(pooled["pairs"].as<int>(), 4);
  EXPECT_DOUBLE_EQ(pooled["median_ate_ratio"].as<double>(), 0.275);
  EXPECT_DOUBLE_EQ(pooled["fraction_subject_lower"].as<double>(), 1.0);
  EXPECT_DOUBLE_EQ(pooled["wilcoxon_signed_rank"]["p_two_sided"].as<double>(), 0.125);
  EXPECT_EQ(st["paired"]["zero"]["scenes"]["beta"]["pairs"].as<int>(), 1);
  EXPECT_DOUBLE_EQ(root["runs"][0]["distance_m"].as<double>(), 50);
  ASSERT_EQ(root["runs"].size(), 12u);  // the runs list still follows
}

}  // namespace
}  // namespace uampc::app
