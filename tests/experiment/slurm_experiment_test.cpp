// `uampc experiment --backend slurm` against a real Slurm: a one-node cluster (Debian's slurm-wlm
// and munge, tests/slurm/start_cluster.sh) runs a 2 x 2 matrix as a job array; the collected
// results equal a local run's, figure for figure and trajectory for trajectory (lockstep runs are
// deterministic, whatever DDS transport carries them); a run that lost its done marker is the only
// one resubmitted; --collect rebuilds the same results.json. Skipped (not passed) where the
// cluster cannot start for lack of root. Also the Kubernetes manifest's tasks, run as its Indexed
// Job would run them (IndexedJobManifest, below), and the errors of --collect and --run-task.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "../e2e/command_runner.hpp"
#include "../e2e/test_domains.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSkipped = 77;  // start_cluster.sh: "needs root"

// The cluster of one test, stopped however the test ends.
class OneNodeCluster {
 public:
  explicit OneNodeCluster(const std::string& directory) : directory_(directory) {
    fs::create_directories(directory_);
    const CommandResult r = runShell("bash " + sourcePath("tests/slurm/start_cluster.sh") + " " + directory_);
    started_ = r.exit_code == 0;
    exit_code_ = r.exit_code;
    output_ = r.output;
  }
  ~OneNodeCluster() {
    if (started_) runShell("bash " + sourcePath("tests/slurm/stop_cluster.sh") + " " + directory_);
  }
  bool started() const { return started_; }
  int exitCode() const { return exit_code_; }
  const std::string& output() const { return output_; }
  // `uampc ARGS` with the cluster's client environment.
  CommandResult uampc(const std::string& args) const {
    return runShell(". " + directory_ + "/env.sh && UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " +
                    binaryPath("bin/uampc") + " " + args);
  }

 private:
  std::string directory_, output_;
  bool started_ = false;
  int exit_code_ = -1;
};

YAML::Node runsOf(const std::string& out) { return YAML::LoadFile(out + "/results.json")["runs"]; }

// The figures of every run, which do not depend on where or how fast it ran.
void expectSameFigures(const std::string& a, const std::string& b) {
  const YAML::Node runs_a = runsOf(a), runs_b = runsOf(b);
  ASSERT_EQ(runs_a.size(), runs_b.size());
  for (std::size_t i = 0; i < runs_a.size(); ++i) {
    const std::string directory = runs_a[i]["directory"].as<std::string>();
    EXPECT_EQ(directory, runs_b[i]["directory"].as<std::string>());
    for (const char* figure : {"ate_m", "ate_aligned_m", "cmplt", "rpe_10m_m", "sim_time_s", "mean_speed"}) {
      EXPECT_EQ(YAML::Dump(runs_a[i][figure]), YAML::Dump(runs_b[i][figure])) << directory << " " << figure;
    }
    EXPECT_EQ(readFile(a + "/" + directory + "/estimate.tum"), readFile(b + "/" + directory + "/estimate.tum"))
        << directory;
  }
}

// DIR/experiment.yaml: the campus scene under UA-MPC and zero speed, with the given duration and
// seeds (YAML lines); returns its path.
std::string writeExperiment(const std::string& dir, const std::string& name, const std::string& duration_and_seeds) {
  const std::string path = dir + "/experiment.yaml";
  std::ofstream(path) << "name: " << name << "\n" << duration_and_seeds << "\nscenes:\n  - {name: campus, scene: "
                      << sourcePath("config/scenes/campus_ua_mpc.yaml")
                      << "}\ncontrollers:\n  - {name: ua_mpc, overrides: [controller.mode=ua_mpc]}\n"
                         "  - {name: zero, overrides: [controller.mode=zero]}\ncompare: {baseline: zero}\n";
  return path;
}

std::vector<std::string> statuses(const std::string& out) {
  std::vector<std::string> s;
  for (const auto& run : runsOf(out)) s.push_back(run["status"].as<std::string>());
  return s;
}

TEST(SlurmExperiment, AJobArrayOnARealClusterGivesTheLocalResultsAndResumes) {
  const std::string dir = freshDirectory("slurm_experiment_test");
  const OneNodeCluster cluster(dir + "/cluster");
  if (cluster.exitCode() == kSkipped) GTEST_SKIP() << cluster.output();
  ASSERT_TRUE(cluster.started()) << cluster.output();

  const std::string experiment = writeExperiment(dir, "slurm_e2e", "duration: 3\nseeds: [1, 2]");
  const std::string on_slurm = dir + "/slurm_out", here = dir + "/local_out";
  const std::string slurm_command = "experiment " + experiment + " --out " + on_slurm + " --backend slurm --domain-base " +
                                    std::to_string(testDomain(DomainBlock::kSlurmExperiment, 0));

  const CommandResult submitted = cluster.uampc(slurm_command);
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("4 array task(s) of 4 runs"), std::string::npos) << submitted.output;
  EXPECT_NE(submitted.output.find("4/4 done, 0 failed"), std::string::npos) << submitted.output;
  EXPECT_EQ(statuses(on_slurm), std::vector<std::string>(4, "ok"));
  // Each run kept its DDS traffic on the host, and says where it ran.
  const std::string log = readFile(on_slurm + "/runs/campus/zero/seed2/scene.yaml");
  EXPECT_NE(log.find("host_only_dds.xml"), std::string::npos) << log;

  const CommandResult local = runUampc("experiment " + experiment + " --out " + here + " --jobs 2 --domain-base " +
                                       std::to_string(testDomain(DomainBlock::kSlurmExperiment, 4)));
  ASSERT_EQ(local.exit_code, 0) << local.output;
  expectSameFigures(on_slurm, here);

  // Resume: only the run without its done marker goes to the cluster again.
  fs::remove(on_slurm + "/runs/campus/ua_mpc/seed2/done");
  const CommandResult resumed = cluster.uampc(slurm_command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("1 array task(s) of 4 runs (the rest finished before)"), std::string::npos)
      << resumed.output;
  const std::string submissions = readFile(on_slurm + "/slurm/submissions.log");
  EXPECT_NE(submissions.find("--array=0-3 "), std::string::npos) << submissions;
  EXPECT_NE(submissions.find("--array=1 "), std::string::npos) << submissions;
  expectSameFigures(on_slurm, here);

  // --collect: the same results from the directories alone.
  const std::string before = readFile(on_slurm + "/results.json");
  fs::remove(on_slurm + "/results.json");
  const CommandResult collected = runUampc("experiment --collect " + on_slurm);
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_NE(collected.output.find("4 of 4 runs of slurm_e2e finished"), std::string::npos) << collected.output;
  expectSameFigures(on_slurm, here);
  EXPECT_EQ(statuses(on_slurm), std::vector<std::string>(4, "ok"));
}

// docker/k8s/experiment-indexed-job.yaml, run as its Indexed Job would run it, as far as a machine
// without Kubernetes can: the manifest is read (an Indexed Job of pods that are not restarted), each
// index runs the container's command with $(JOB_COMPLETION_INDEX) expanded as the kubelet expands
// it and the experiments volume at a directory of the test, then --collect gives a local run's
// results, and a task run again does nothing. The test adds --domain-base only: unlike pods, the
// tasks here share the host's network with other tests. Kubernetes itself is not tested.
TEST(IndexedJobManifest, ItsTasksGiveTheLocalResults) {
  const std::string dir = freshDirectory("indexed_job_test");
  const YAML::Node job = YAML::LoadFile(sourcePath("docker/k8s/experiment-indexed-job.yaml"));
  ASSERT_EQ(job["kind"].as<std::string>(), "Job");
  ASSERT_EQ(job["spec"]["completionMode"].as<std::string>(), "Indexed");
  const YAML::Node pod = job["spec"]["template"]["spec"];
  ASSERT_EQ(pod["restartPolicy"].as<std::string>(), "Never");
  const YAML::Node container = pod["containers"][0];
  std::string volume;
  for (const auto& mount : container["volumeMounts"]) {
    if (mount["name"].as<std::string>() == "experiments") volume = mount["mountPath"].as<std::string>();
  }
  ASSERT_FALSE(volume.empty()) << "no experiments volume in the manifest";
  const auto command = container["command"].as<std::vector<std::string>>();
  ASSERT_GE(command.size(), 2u);
  ASSERT_EQ(command[0], "uampc");
  // A path on the volume, at the test's directory instead (others unchanged).
  const auto onVolume = [&](const std::string& path) {
    return path.rfind(volume, 0) == 0 ? dir + "/volume" + path.substr(volume.size()) : path;
  };
  ASSERT_EQ(command[command.size() - 2], "--out");
  ASSERT_EQ(command.back().rfind(volume, 0), 0u) << "the experiment's directory is not on the volume";
  const std::string out = onVolume(command.back());
  // The command with the index expanded and the volume's paths at the test's directory.
  const auto taskArguments = [&](int index) {
    std::string args;
    for (std::size_t i = 1; i < command.size(); ++i) {
      args += " " + (command[i] == "$(JOB_COMPLETION_INDEX)" ? std::to_string(index) : onVolume(command[i]));
    }
    return args + " --domain-base " + std::to_string(testDomain(DomainBlock::kSlurmExperiment, 8));
  };

  const std::string experiment = writeExperiment(dir, "k8s_e2e", "duration: 2\nseeds: [1]");
  const CommandResult planned = runUampc("experiment " + experiment + " --out " + out + " --plan-only");
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  EXPECT_NE(planned.output.find("completions: 2"), std::string::npos) << planned.output;
  for (int index = 0; index < 2; ++index) {
    const CommandResult task = runUampc(taskArguments(index));
    ASSERT_EQ(task.exit_code, 0) << task.output;
  }
  const CommandResult again = runUampc(taskArguments(1));
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("finished before; nothing to do"), std::string::npos) << again.output;

  const CommandResult collected = runUampc("experiment --collect " + out);
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_NE(collected.output.find("2 of 2 runs of k8s_e2e finished"), std::string::npos) << collected.output;
  const std::string here = dir + "/local_out";
  const CommandResult local = runUampc("experiment " + experiment + " --out " + here + " --jobs 2 --domain-base " +
                                       std::to_string(testDomain(DomainBlock::kSlurmExperiment, 9)));
  ASSERT_EQ(local.exit_code, 0) << local.output;
  expectSameFigures(out, here);
}

TEST(SlurmExperiment, CollectAndRunTaskSayWhatIsWrong) {
  const std::string dir = freshDirectory("slurm_experiment_errors");
  CommandResult r = runUampc("experiment --collect " + dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(dir + "/experiment.json: error: no such file"), std::string::npos) << r.output;
  std::ofstream(dir + "/experiment.json") << "{\"version\": 1, \"experiment\": {\"name\": 3}}";
  r = runUampc("experiment --run-task 0 --out " + dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(dir + "/experiment.json: error:"), std::string::npos) << r.output;
  r = runUampc("experiment x.yaml --collect " + dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("give no EXPERIMENT.yaml"), std::string::npos) << r.output;
  r = runUampc("experiment " + sourcePath("config/experiments/paper_core.yaml") + " --out " + dir + " --partition p");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("need --backend slurm"), std::string::npos) << r.output;
}

// The Slurm backend's own records on a full disk (docs/decisions/run-files-whole-or-absent.md),
// against a stand-in sbatch that answers job 4242 and a stand-in scancel that notes what it was
// asked: a submission that cannot be logged, or a job id that cannot be recorded, stops the
// experiment naming the file (exit code 1), and the job is cancelled, since nothing would watch or
// collect it. Before, both appends went unchecked: the experiment went on, exit code 0.
TEST(SlurmExperiment, ASubmissionThatCannotBeRecordedStopsNamingTheFileAndCancelsTheJob) {
  const std::string dir = freshDirectory("slurm_unrecorded");
  const std::string fake_bin = dir + "/bin", scancel_log = dir + "/scancel.args";
  fs::create_directories(fake_bin);
  std::ofstream(fake_bin + "/sbatch") << "#!/bin/sh\necho 4242\n";
  std::ofstream(fake_bin + "/scancel") << "#!/bin/sh\necho \"$@\" >> " << scancel_log << "\n";
  for (const char* tool : {"/sbatch", "/scancel"}) fs::permissions(fake_bin + tool, fs::perms::owner_all);
  const std::string experiment = writeExperiment(dir, "slurm_unrecorded", "duration: 3\nseeds: [1]");
  const auto submit = [&](const std::string& out) {
    return runShell("PATH=" + fake_bin + ":$PATH UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " +
                    binaryPath("bin/uampc") + " experiment " + experiment + " --out " + out +
                    " --backend slurm --no-wait");
  };

  // submissions.log on a full disk: /dev/full fails every write with ENOSPC.
  const std::string full_log = dir + "/full_log";
  fs::create_directories(full_log + "/slurm");
  fs::create_symlink("/dev/full", full_log + "/slurm/submissions.log");
  CommandResult r = submit(full_log);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write " + full_log + "/slurm/submissions.log: No space left on device; slurm job "
                          "4242 was cancelled"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(readFile(scancel_log), "4242\n");
  EXPECT_FALSE(fs::exists(full_log + "/slurm/jobs"));

  // The job list cannot be made (a directory in its way): the log has the submission, the job is
  // cancelled.
  const std::string no_jobs = dir + "/no_jobs";
  fs::create_directories(no_jobs + "/slurm/jobs");
  r = submit(no_jobs);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write " + no_jobs + "/slurm/jobs: Is a directory; slurm job 4242 was cancelled"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(readFile(scancel_log), "4242\n4242\n");
  EXPECT_NE(readFile(no_jobs + "/slurm/submissions.log").find("--array=0-1 "), std::string::npos);

  // Recorded: the job is watched no further (--no-wait) and left running.
  const std::string fine = dir + "/fine";
  r = submit(fine);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(readFile(fine + "/slurm/jobs"), "4242\n");
  EXPECT_EQ(readFile(scancel_log), "4242\n4242\n");
}

}  // namespace
}  // namespace uampc::test
