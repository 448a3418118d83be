// The paper's table from hand-made run directories (fake_runs.cpp lists their figures).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "command_runner.hpp"
#include "report/test/fake_runs.hpp"
#include "report/results_table.hpp"

namespace uampc::app {
namespace {

TEST(ResultsTable, MeansOverSeedsSumsAndRatios) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("results_table_test"));
  const ResultsTable t = summarize(fake.experiment, fake.results);
  ASSERT_EQ(t.controllers, (std::vector<std::string>{"ua_mpc", "constant_3.6", "zero"}));
  ASSERT_EQ(t.scenes, (std::vector<std::string>{"alpha", "beta"}));
  EXPECT_DOUBLE_EQ(t.ate[0][0].mean, 1.5);
  EXPECT_DOUBLE_EQ(t.ate[1][0].mean, 5.0);
  EXPECT_DOUBLE_EQ(t.ate[0][1].mean, 3.5);
  EXPECT_DOUBLE_EQ(t.ate[1][1].mean, 15.0);
  EXPECT_DOUBLE_EQ(t.ate[2][1].mean, 29.5);  // the failed seed is left out
  EXPECT_EQ(t.ate[2][1].runs, 1);
  EXPECT_DOUBLE_EQ(t.cmplt[0][0].mean, 105.0);
  EXPECT_TRUE(std::isnan(t.cmplt[2][0].mean));  // null in metrics.json
  EXPECT_DOUBLE_EQ(t.ate_sum[0], 5.0);
  EXPECT_DOUBLE_EQ(t.ate_sum[1], 20.0);
  EXPECT_DOUBLE_EQ(t.ate_sum_ratio[0], 0.25);
  EXPECT_DOUBLE_EQ(t.ate_sum_ratio[1], 1.0);
  EXPECT_DOUBLE_EQ(t.cmplt_ratio[0][0], 1.05);
  EXPECT_DOUBLE_EQ(t.cmplt_ratio[0][1], 1.0);
  EXPECT_DOUBLE_EQ(t.cmplt_ratio[2][1], 0.4);
  EXPECT_EQ(headline(t),
            "ua_mpc against constant_3.6: ATE summed over scenes -75.0% (the paper: more than 60% lower); CMPLT "
            "alpha +5.0%, beta +0.0% (the paper: less than 2% lower).");
}

TEST(ResultsTable, MarkdownHasThePapersColumnsAndMarksMissingSeeds) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("results_table_md_test"));
  const std::string md = renderMarkdown(fake.experiment, summarize(fake.experiment, fake.results), fake.results);
  EXPECT_NE(md.find("| controller | alpha ATE m | alpha CMPLT | beta ATE m | beta CMPLT | ATE sum m | "
                    "ATE sum / constant_3.6 | alpha CMPLT / constant_3.6 | beta CMPLT / constant_3.6 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| ua_mpc | 1.50 | 105 | 3.50 | 50 | 5.00 | 0.25 | 1.05 | 1.00 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| zero | 8.50 | n/a | 29.50 (1/2) | 20 (1/2) | 38.00 | 1.90 | n/a | 0.40 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| beta | zero | 2 | failed: exit code 1 |"), std::string::npos) << md;
}

TEST(ResultsTable, CountsLossesOfTrackThatMeansHide) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("results_table_lost_test"));
  const ResultsTable t = summarize(fake.experiment, fake.results);
  EXPECT_EQ(t.lost_runs[0], (std::vector<int>{0, 0}));  // ua_mpc
  EXPECT_EQ(t.lost_runs[1], (std::vector<int>{0, 1}));  // constant_3.6: beta seed 2
  EXPECT_EQ(t.lost_runs[2], (std::vector<int>{2, 0}));  // zero: both alpha seeds
  EXPECT_EQ(t.finished_runs[2], (std::vector<int>{2, 1}));
  // Losses within the first 10 s are the start's, counted apart: zero's alpha seed 2 lost at 14.25 s.
  EXPECT_EQ(t.start_up_lost_runs[1], (std::vector<int>{0, 1}));
  EXPECT_EQ(t.start_up_lost_runs[2], (std::vector<int>{1, 0}));
  const std::string md = renderMarkdown(fake.experiment, t, fake.results);
  EXPECT_NE(md.find("| constant_3.6 | 0 lost of 2 | 1 lost of 2 (1 at start-up) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| zero | 2 lost of 2 (1 at start-up) | 0 lost of 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| beta | constant_3.6 | 2 | reused | 20.000 | 10.000 | 60 | 66 | 3.60 | 7.0 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| beta | ua_mpc | 1 | reused | 3.000 | 1.500 | 50 | 55 | 3.60 | never |"), std::string::npos) << md;
}

// A run that held only thanks to the LO's velocity resets is counted as recovered, apart from the
// runs that held without them and from those lost.
TEST(ResultsTable, CountsRunsThatRecoveredApart) {
  auto fake = test::makeFakeExperiment(test::freshDirectory("results_table_recovered_test"));
  for (RunResult& r : fake.results) {
    if (r.controller == "ua_mpc" && r.scene == "alpha" && r.seed == 1) r.metrics.velocity_resets = 3;
    if (r.controller == "zero" && r.scene == "alpha") r.metrics.velocity_resets = 5;  // lost all the same
  }
  const ResultsTable t = summarize(fake.experiment, fake.results);
  EXPECT_EQ(t.recovered_runs[0], (std::vector<int>{1, 0}));
  EXPECT_EQ(t.recovered_runs[2], (std::vector<int>{0, 0}));
  const std::string md = renderMarkdown(fake.experiment, t, fake.results);
  EXPECT_NE(md.find("| ua_mpc | 0 lost of 2, 1 recovered | 0 lost of 2 |"), std::string::npos) << md;
}

TEST(ResultsJson, EveryRunWithItsFigures) {
  const auto fake = test::makeFakeExperiment(test::freshDirectory("results_json_test"));
  const std::string path = fake.directory + "/results.json";
  writeResultsJson(path, fake.experiment, fake.results);
  const YAML::Node root = YAML::LoadFile(path);  // JSON is YAML: a parse checks it is well formed
  ASSERT_EQ(root["runs"].size(), 12u);
  const YAML::Node first = root["runs"][0];
  EXPECT_EQ(first["scene"].as<std::string>(), "alpha");
  EXPECT_EQ(first["controller"].as<std::string>(), "ua_mpc");
  EXPECT_EQ(first["seed"].as<int>(), 1);
  EXPECT_EQ(first["status"].as<std::string>(), "reused");
  EXPECT_DOUBLE_EQ(first["ate_m"].as<double>(), 1.0);
  EXPECT_DOUBLE_EQ(first["ate_aligned_m"].as<double>(), 0.5);
  EXPECT_DOUBLE_EQ(first["cmplt"].as<double>(), 100);
  EXPECT_DOUBLE_EQ(first["cmplt_ground_truth"].as<double>(), 110);
  EXPECT_DOUBLE_EQ(first["rpe_10m_m"].as<double>(), 0.5);
  EXPECT_TRUE(first["rpe_100m_m"].IsNull());
  EXPECT_DOUBLE_EQ(first["sim_time_s"].as<double>(), 10);
  EXPECT_DOUBLE_EQ(first["wall_time_s"].as<double>(), 4.5);
  EXPECT_DOUBLE_EQ(first["real_time_factor"].as<double>(), 2.5);
  EXPECT_TRUE(first["lost_track_at_s"].IsNull());
  EXPECT_DOUBLE_EQ(root["runs"][4]["lost_track_at_s"].as<double>(), 3.5);  // alpha, zero, seed 1
  EXPECT_EQ(root["runs"][11]["status"].as<std::string>(), "failed");
}

TEST(LauncherSummary, ParsesTheLastLine) {
  const auto s = parseLauncherSummary(
      "uampc: sim 5.0 / 5.0 s (100%), 1.8x real time\n"
      "uampc: 5 s of sim time in 2.7702 s (1.80492x real time)\n done.\n");
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->sim_s, 5);
  EXPECT_DOUBLE_EQ(s->wall_s, 2.7702);
  EXPECT_DOUBLE_EQ(s->real_time_factor, 1.80492);
  EXPECT_FALSE(parseLauncherSummary("uampc: run failed\n"));
}

}  // namespace
}  // namespace uampc::app
