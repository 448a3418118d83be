// The uampc command line itself (apps/uampc/main.cpp): help for every command, --version, and
// command-line mistakes that exit 2 with a message naming what was wrong, before anything runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "command_runner.hpp"

namespace uampc::test {
namespace {

struct CommandOptions {
  std::string command;
  std::vector<std::string> options;  // every one must be in `uampc COMMAND --help`
};

const std::vector<CommandOptions> kCommands = {
    {"launch", {"SCENE.yaml", "--set NAME=VALUE", "--out DIR"}},
    {"validate", {"SCENE.yaml", "--set NAME=VALUE"}},
    {"graph", {"SCENE.yaml", "--set NAME=VALUE", "--format mermaid|dot"}},
    {"experiment",
     {"EXPERIMENT.yaml", "--out DIR", "--jobs N", "--data-dir DIR", "--domain-base N", "--set NAME=VALUE",
      "--dry-run"}},
    {"components", {"--json"}},
    {"run-process", {"SCENE.yaml", "--process NAME", "--own-clock", "--set NAME=VALUE", "--out DIR"}},
    {"clock", {"SCENE.yaml", "--set NAME=VALUE"}},
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(CommandLine, EveryCommandHasHelpThatNamesEachOfItsOptions) {
  for (const auto& [command, options] : kCommands) {
    const CommandResult r = runUampc(command + " --help");
    EXPECT_EQ(r.exit_code, 0) << command << ":\n" << r.output;
    EXPECT_TRUE(contains(r.output, "usage: uampc " + command)) << r.output;
    // Listed in the options table (two spaces in front), not only in the synopsis.
    for (const auto& option : options) EXPECT_TRUE(contains(r.output, "  " + option)) << command << ": " << option;
  }
}

TEST(CommandLine, TopLevelHelpListsEveryCommand) {
  const CommandResult r = runUampc("--help");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const auto& c : kCommands) EXPECT_TRUE(contains(r.output, "  uampc " + c.command + " ")) << c.command;
  EXPECT_TRUE(contains(r.output, "--version")) << r.output;
}

TEST(CommandLine, NoArgumentsPrintsTheUsageAndExits2) {
  const CommandResult r = runUampc("");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "uampc launch SCENE.yaml")) << r.output;
}

TEST(CommandLine, VersionNamesUampcsBuildAndFastDds) {
  const CommandResult r = runUampc("--version");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // git describe --always --dirty --tags (a tag or commit, maybe -dirty), or "unknown" outside git.
  EXPECT_TRUE(std::regex_search(r.output, std::regex("^uampc [0-9A-Za-z._-]+\n"))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("\nFast DDS 2\\.9\\.[0-9]+"))) << r.output;
}

TEST(CommandLine, AnUnknownOptionExits2AndIsNamed) {
  CommandResult r = runUampc("validate " + sourcePath("config/scenes/default.yaml") + " --bogus-option");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--bogus-option")) << r.output;
  r = runUampc("--bogus-option");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "unknown option '--bogus-option'")) << r.output;
}

TEST(CommandLine, AnUnknownCommandExits2AndIsNamed) {
  const CommandResult r = runUampc("lanch " + sourcePath("config/scenes/default.yaml"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "unknown command 'lanch'")) << r.output;
}

TEST(CommandLine, MissingRequiredArgumentsExit2AndAreNamed) {
  CommandResult r = runUampc("launch");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "SCENE.yaml is required")) << r.output;
  r = runUampc("run-process " + sourcePath("config/scenes/default_split.yaml"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--process is required")) << r.output;
  // Stepping itself only where the scene says its processes do: beside the launcher's clock, both
  // would step the run.
  r = runUampc("run-process " + sourcePath("config/scenes/default_split.yaml") +
               " --process motor --own-clock --set clock.in_process=false");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--own-clock lets the process groups of a lockstep scene with clock.in_process: true "
                                 "step themselves; this scene has clock.in_process: false"))
      << r.output;
  r = runUampc("experiment " + sourcePath("config/experiments/paper_core.yaml"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--out is required")) << r.output;
}

// NaN and infinity pass CLI11's own range checks; each number of the command line is refused
// unless finite (`play --rate nan` played forever).
TEST(CommandLine, NumbersMustBeFinite) {
  for (const std::string args : {"play x.mcap --rate nan", "play x.mcap --start nan", "record -o x.mcap --duration nan",
                                 "topic list --wait nan", "play x.mcap --rate inf"}) {
    const CommandResult r = runUampc(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, "is not a finite number")) << args << "\n" << r.output;
  }
}

// A refused number is named with its value and what is wanted, in words, not CLI11's bound of
// 1.8e308 written out in 300 digits.
TEST(CommandLine, RefusedNumbersAreSaidShortly) {
  for (const auto& [args, wanted] : {std::pair<std::string, std::string>{"topic echo /x -n 0", "'0' is not a whole number of 1 or more"},
                                     {"topic hz /x --window -7", "'-7' is not a whole number of 1 or more"},
                                     {"record -o x.mcap --duration -1", "'-1' must not be negative"}}) {
    const CommandResult r = runUampc(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, wanted)) << args << "\n" << r.output;
    EXPECT_FALSE(contains(r.output, "179769313486231570")) << args << "\n" << r.output;
  }
}

TEST(CommandLine, SetTakesOneValueAndMayComeBeforeTheScene) {
  // --set is repeatable but takes one value each time: the scene after it is the scene.
  const CommandResult r =
      runUampc("validate --set clock.duration=2 --set seed=3 " + sourcePath("config/scenes/default.yaml"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(CommandLine, AMalformedSetExits2WithTheOverrideParsersMessage) {
  const CommandResult r = runUampc("validate " + sourcePath("config/scenes/default.yaml") + " --set clock.duration");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--set clock.duration: error: expected NAME=VALUE")) << r.output;
}

TEST(CommandLine, ExperimentOptionsAreCheckedBeforeAnythingRuns) {
  const std::string dir = freshDirectory("command_line_experiment");
  const std::string experiment = "experiment " + sourcePath("config/experiments/paper_core.yaml") + " --out " + dir;
  CommandResult r = runUampc(experiment + " --set seed=3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--set seed=3: seed is set by the experiment")) << r.output;
  r = runUampc(experiment + " --jobs 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--jobs")) << r.output;
  r = runUampc(experiment + " --jobs 100 --domain-base 200");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "needs DDS domains above 232")) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/runs"));
}

TEST(CommandLine, GraphFormatIsMermaidOrDot) {
  const CommandResult r = runUampc("graph " + sourcePath("config/scenes/default.yaml") + " --format svg");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--format: svg not in {mermaid,dot}")) << r.output;
}

}  // namespace
}  // namespace uampc::test
