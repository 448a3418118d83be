// The CI files (docs/dev/testing.md, "Sanitizers and CI") checked as their services read them, without the network:
// .github/workflows/ci.yml with GitHub's own workflow parser, .gitlab-ci.yml against GitLab's CI
// schema (tests/ci_lint/lint_ci.mjs). Both must hold the two jobs users rely on: the Docker image
// (which runs the test suite) and the ASan/UBSan workflow preset in debian:12 with a ccache cache.
// Deliberately broken copies are rejected, with file and line, so that the check can fail.
//
// Needs node and `npm ci --prefix tests/ci_lint` (docker/install-deps.sh does both): without them
// the test fails, unless UAMPC_SKIP_JS=1 is set.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../e2e/command_runner.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

const std::string kGithubWorkflow = ".github/workflows/ci.yml";
const std::string kGitlabFile = ".gitlab-ci.yml";

bool skipRequested() {
  const char* skip = std::getenv("UAMPC_SKIP_JS");
  return skip && std::string(skip) == "1";
}

// Fails the test (does not skip it) when node or the npm packages are missing.
void requireLinter() {
  ASSERT_EQ(std::system("command -v node >/dev/null 2>&1"), 0)
      << "node is not installed (docker/install-deps.sh installs it; UAMPC_SKIP_JS=1 skips this test)";
  ASSERT_TRUE(fs::exists(fs::path(UAMPC_CI_LINT_DIR) / "node_modules" / "@actions" / "workflow-parser"))
      << "run `npm ci --prefix tests/ci_lint` (docker/install-deps.sh does; UAMPC_SKIP_JS=1 skips this test)";
}

CommandResult lint(const std::string& kind, const std::string& file) {
  return runShell("node '" + std::string(UAMPC_CI_LINT_DIR) + "/lint_ci.mjs' " + kind + " '" + file + "'");
}

// A copy of a committed CI file with `from` replaced by `to` (which must be there).
std::string brokenCopy(const std::string& relative, const std::string& from, const std::string& to,
                       const std::string& name) {
  std::string text = readFile(sourcePath(relative));
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("'" + from + "' is not in " + relative);
  text.replace(at, from.size(), to);
  const std::string path = freshDirectory("ci_lint_" + name) + "/" + fs::path(relative).filename().string();
  std::ofstream(path) << text;
  return path;
}

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in:\n" << text;
}

// What each CI file's two jobs must say: the Docker image (which runs the tests), and the asan
// workflow in debian:12 with ccache.
const char* const kBothJobs[] = {"docker build --shm-size=2g -f docker/Dockerfile", "image: debian:12",
                                 "bash docker/install-deps.sh", "cmake --workflow --preset asan",
                                 "CMAKE_CXX_COMPILER_LAUNCHER: ccache"};

class CiLint : public ::testing::Test {
 protected:
  void SetUp() override {
    if (skipRequested()) GTEST_SKIP() << "UAMPC_SKIP_JS=1";
    requireLinter();
  }
};

TEST_F(CiLint, CommittedGithubWorkflowIsValidAndHasBothJobs) {
  const CommandResult result = lint("github", sourcePath(kGithubWorkflow));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string text = readFile(sourcePath(kGithubWorkflow));
  for (const char* line : kBothJobs) expectContains(text, line);
  expectContains(text, "uses: actions/cache@");
}

TEST_F(CiLint, CommittedGitlabFileIsValidAndHasBothJobs) {
  const CommandResult result = lint("gitlab", sourcePath(kGitlabFile));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string text = readFile(sourcePath(kGitlabFile));
  for (const char* line : kBothJobs) expectContains(text, line);
  expectContains(text, "- .ccache/");
}

TEST_F(CiLint, GithubWorkflowWithAMisspelledKeyIsRejectedWithItsLine) {
  const std::string file = brokenCopy(kGithubWorkflow, "    runs-on: ubuntu-latest\n    timeout-minutes: 60",
                                      "    runs_on: ubuntu-latest\n    timeout-minutes: 60", "misspelled");
  const CommandResult result = lint("github", file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  expectContains(result.output, "Unexpected value 'runs_on'");
  expectContains(result.output, "Required property is missing: runs-on");
  expectContains(result.output, file + ":");
}

TEST_F(CiLint, GithubWorkflowWithABrokenExpressionIsRejected) {
  const std::string file =
      brokenCopy(kGithubWorkflow, "${{ github.workspace }}/.ccache", "${{ github.workspace( }}/.ccache", "expression");
  const CommandResult result = lint("github", file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  expectContains(result.output, "Unexpected symbol: '('");
}

TEST_F(CiLint, GitlabFileWithAnUnknownJobKeyIsRejectedWithItsLine) {
  const std::string file = brokenCopy(kGitlabFile, "  script:\n    - bash docker/install-deps.sh",
                                      "  scripts:\n    - bash docker/install-deps.sh", "unknown_key");
  const CommandResult result = lint("gitlab", file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  expectContains(result.output, "/asan must NOT have additional properties 'scripts'");
  expectContains(result.output, file + ":");
}

TEST_F(CiLint, GitlabFileWithAWrongTypeIsRejected) {
  const std::string file = brokenCopy(kGitlabFile, "  image: debian:12", "  image: [debian, 12]", "wrong_type");
  const CommandResult result = lint("gitlab", file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  expectContains(result.output, "/asan/image");
}

TEST_F(CiLint, CiFileThatIsNotYamlIsRejected) {
  const std::string file = brokenCopy(kGitlabFile, "  timeout: 90m", "  timeout: [90m", "not_yaml");
  const CommandResult result = lint("gitlab", file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  expectContains(result.output, "Flow sequence");
}

}  // namespace
}  // namespace uampc::test
