#include "experiment/backends/slurm_backend.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "experiment/experiment_collect.hpp"
#include "experiment/backends/experiment_runner.hpp"
#include "external_command.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace uampc::app {

namespace {

// Shared memory, and UDP on the loopback interface only (as ROS 2's ROS_LOCALHOST_ONLY configures
// Fast DDS): a run's participants find each other, and nothing on another host finds them.
constexpr char kHostOnlyProfileXml[] = R"(<?xml version="1.0" encoding="UTF-8" ?>
<!-- Written by `uampc experiment --backend slurm`: keeps each run's DDS traffic on its own host. -->
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>host_shm</transport_id>
        <type>SHM</type>
      </transport_descriptor>
      <transport_descriptor>
        <transport_id>host_udp</transport_id>
        <type>UDPv4</type>
        <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="uampc_host_only" is_default_profile="true">
      <rtps>
        <userTransports>
          <transport_id>host_shm</transport_id>
          <transport_id>host_udp</transport_id>
        </userTransports>
        <useBuiltinTransports>false</useBuiltinTransports>
      </rtps>
    </participant>
  </profiles>
</dds>
)";

fs::path slurmDirectory(const std::string& output_directory) { return fs::path(output_directory) / "slurm"; }

ExternalCommandResult slurmCommand(const std::vector<std::string>& argv, const std::string& output_directory) {
  const fs::path scratch = slurmDirectory(output_directory) / (".output." + std::to_string(getpid()));
  return runExternalCommand(argv, scratch.string());
}

std::vector<std::string> submittedJobs(const std::string& output_directory) {
  std::vector<std::string> jobs;
  std::istringstream in(run_files::readTextFile(slurmDirectory(output_directory) / "jobs"));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) jobs.push_back(line);
  }
  return jobs;
}

// The states of a job's tasks still queued or running ("PENDING", "RUNNING", ...), from squeue;
// nullopt when squeue failed for another reason than the job being gone.
std::optional<std::vector<std::string>> activeTaskStates(const std::string& job, const std::string& output_directory,
                                                         std::string* error) {
  const ExternalCommandResult r = slurmCommand({"squeue", "--noheader", "--array", "--jobs", job, "--format", "%T"},
                                               output_directory);
  std::vector<std::string> states;
  if (r.started && r.exit_code != 0 && r.output.find("Invalid job id") != std::string::npos) return states;
  if (!r.ok()) {
    if (error) *error = r.started ? r.output : "cannot run squeue: " + r.error;
    return std::nullopt;
  }
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) states.push_back(line);
  }
  return states;
}

// "COMPLETED 3, FAILED 1": how the array's tasks ended, from sacct where the cluster keeps
// accounting (slurmdbd), else from squeue, which lists ended jobs for MinJobAge (300 s by default);
// empty when neither knows.
std::string finalStates(const std::string& job, const std::string& output_directory) {
  ExternalCommandResult r = slurmCommand(
      {"sacct", "--noheader", "--parsable2", "--allocations", "--jobs", job, "--format", "State"}, output_directory);
  std::string source = "sacct";
  if (!r.ok() || r.output.empty()) {
    r = slurmCommand({"squeue", "--noheader", "--array", "--states", "all", "--jobs", job, "--format", "%T"},
                     output_directory);
    source = "squeue";
  }
  if (!r.ok()) return "";
  std::map<std::string, int> counts;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) ++counts[line.substr(0, line.find(' '))];
  }
  std::string text;
  for (const auto& [state, n] : counts) text += (text.empty() ? "" : ", ") + state + " " + std::to_string(n);
  return text.empty() ? "" : source + ": " + text;
}

std::string quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The job array's batch script: one task runs one planned run.
std::string batchScript(const std::string& output_directory, int domain_base) {
  return "#!/bin/sh\n"
         "# One run of a uampc experiment per array task; written by `uampc experiment --backend slurm`.\n"
         "exec " +
         quoted(fs::canonical("/proc/self/exe").string()) + " experiment --run-task \"$SLURM_ARRAY_TASK_ID\" --out " +
         quoted(output_directory) + " --domain-base " + std::to_string(domain_base) + "\n";
}

// Runs not done (run_completion.hpp): what a submission runs.
std::vector<std::size_t> unfinishedRuns(const ExperimentSnapshot& snapshot, const std::string& output_directory) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < snapshot.plan.size(); ++i) {
    const PlannedRun& run = snapshot.plan[i];
    if (!isRunComplete((fs::path(output_directory) / run.directory).string(), run.end)) indices.push_back(i);
  }
  return indices;
}

// Appends the submission to slurm/submissions.log and its job id (if sbatch gave one) to
// slurm/jobs, each whole or not at all. A job that cannot be recorded is cancelled: a later run of
// the command would not know to wait for it, and --collect would not know of it. Throws
// std::runtime_error naming the file and what became of the job
// (docs/decisions/run-files-whole-or-absent.md).
void recordSubmission(const fs::path& slurm, const std::string& log_entry, const std::string& job,
                      const std::string& output_directory) {
  try {
    run_files::appendToTextFile(slurm / "submissions.log", log_entry);
    if (!job.empty()) run_files::appendToTextFile(slurm / "jobs", job + "\n");
  } catch (const std::runtime_error& e) {
    if (job.empty()) throw;
    const ExternalCommandResult cancel = slurmCommand({"scancel", job}, output_directory);
    throw std::runtime_error(std::string(e.what()) + "; slurm job " + job +
                             (cancel.ok() ? " was cancelled (not recorded, it would run unwatched)"
                                          : " is not recorded and could not be cancelled (" +
                                                (cancel.started ? cancel.output : cancel.error) +
                                                "): `scancel " + job + "` stops it"));
  }
}

// sbatch's job id, or "" with the reason printed.
std::string submit(const std::vector<std::size_t>& runs, const std::string& output_directory,
                   const SlurmOptions& options, const std::string& name) {
  const fs::path slurm = slurmDirectory(output_directory);
  const fs::path script = slurm / "array.sh";
  run_files::writeTextFile(script, batchScript(output_directory, options.domain_base));
  std::vector<std::string> argv = {"sbatch",
                                   "--parsable",
                                   "--job-name=uampc-" + name,
                                   "--array=" + slurmArraySpec(runs),
                                   "--ntasks=1",
                                   "--cpus-per-task=1",
                                   "--output=" + (slurm / "task-%A_%a.out").string()};
  if (!options.partition.empty()) argv.push_back("--partition=" + options.partition);
  if (!options.time_limit.empty()) argv.push_back("--time=" + options.time_limit);
  argv.insert(argv.end(), options.sbatch_options.begin(), options.sbatch_options.end());
  argv.push_back(script.string());
  const ExternalCommandResult r = slurmCommand(argv, output_directory);
  std::smatch id;
  const std::regex job_line(R"((^|\n)([0-9]+)(;[^\n]*)?\s*$)");
  const std::string job = r.ok() && std::regex_search(r.output, id, job_line) ? id[2].str() : "";
  recordSubmission(slurm, commandText(argv) + "\n" + r.output, job, output_directory);
  if (!r.started) {
    std::cerr << "uampc experiment: cannot run sbatch (" << r.error
              << "): --backend slurm needs Slurm's client commands (Debian: slurm-client) on this machine\n";
    return "";
  }
  if (job.empty()) {
    std::cerr << "uampc experiment: sbatch refused the job (" << commandText(argv) << "):\n" << r.output;
  }
  return job;
}

struct DirectoryCounts {
  std::size_t done = 0, failed = 0, started = 0;
};

// What the submitted runs' directories say: finished, failed, or started (a run log, no marker).
DirectoryCounts countRuns(const ExperimentSnapshot& snapshot, const std::vector<std::size_t>& runs,
                          const std::string& output_directory) {
  DirectoryCounts c;
  for (std::size_t i : runs) {
    const std::string dir = (fs::path(output_directory) / snapshot.plan[i].directory).string();
    const RunState state = runCompletion(dir, snapshot.plan[i].end).state;
    if (state == RunState::kDone)
      ++c.done;
    else if (state == RunState::kFailed)
      ++c.failed;
    else if (fs::exists(fs::path(dir) / run_files::kRunLog))
      ++c.started;
  }
  return c;
}

// Watches the job until none of its tasks is queued or running; false when the user stopped watching.
bool watch(const ExperimentSnapshot& snapshot, const std::vector<std::size_t>& runs, const std::string& job,
           const std::string& output_directory, const SlurmOptions& options) {
  catchStopSignals();
  const auto start = Clock::now();
  std::string last_line;
  auto last_print = Clock::time_point{};
  while (!stopRequested()) {
    std::string error;
    const auto states = activeTaskStates(job, output_directory, &error);
    const DirectoryCounts c = countRuns(snapshot, runs, output_directory);
    std::size_t queued = 0;
    if (states) {
      for (const auto& s : *states) queued += s == "PENDING";
    }
    const long elapsed = std::lround(std::chrono::duration<double>(Clock::now() - start).count());
    const std::string line = "experiment: slurm job " + job + ": " + std::to_string(c.done) + "/" +
                             std::to_string(runs.size()) + " done, " + std::to_string(c.failed) + " failed, " +
                             (states ? std::to_string(states->size() - queued) + " running, " +
                                           std::to_string(queued) + " queued"
                                     : "squeue failed: " + error.substr(0, error.find('\n'))) +
                             ", elapsed " + std::to_string(elapsed) + " s";
    const bool changed = line.substr(0, line.find(", elapsed")) != last_line.substr(0, last_line.find(", elapsed"));
    if (changed || Clock::now() - last_print > std::chrono::seconds(60)) {
      std::cerr << line << "\n";
      last_line = line;
      last_print = Clock::now();
    }
    if (states && states->empty()) return true;
    const auto until = Clock::now() + std::chrono::duration<double>(options.poll_interval_s);
    while (Clock::now() < until && !stopRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::cerr << "uampc experiment: stopped watching; slurm job " << job << " goes on (`scancel " << job
            << "` stops it). Later: uampc experiment --collect " << output_directory << "\n";
  return false;
}

}  // namespace

std::string hostOnlyDdsOverride(const std::string& output_directory) {
  return "dds_profile=" + (fs::path(output_directory) / kHostOnlyDdsProfile).string();
}

void writeHostOnlyDdsProfile(const std::string& output_directory) {
  const fs::path path = fs::path(output_directory) / kHostOnlyDdsProfile;
  fs::create_directories(path.parent_path());
  run_files::writeTextFile(path, kHostOnlyProfileXml);
}

std::string slurmArraySpec(const std::vector<std::size_t>& indices) {
  std::string spec;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    spec += (spec.empty() ? "" : ",") + std::to_string(indices[k]);
    if (end > k) spec += "-" + std::to_string(indices[end]);
    k = end + 1;
  }
  return spec;
}

BackendOutcome runOnSlurm(const ExperimentSnapshot& snapshot, const std::string& output_directory,
                          const SlurmOptions& options) {
  fs::create_directories(slurmDirectory(output_directory));
  for (const std::string& job : submittedJobs(output_directory)) {
    const auto states = activeTaskStates(job, output_directory, nullptr);
    if (states && !states->empty()) {
      std::cerr << "uampc experiment: slurm job " << job << " of " << output_directory
                << " is still queued or running; wait for it to end (or `scancel " << job
                << "`), then run this again to resubmit what did not finish\n";
      return {std::nullopt, 2};
    }
  }
  writeExperimentSnapshot(output_directory, snapshot);
  const std::vector<std::size_t> runs = unfinishedRuns(snapshot, output_directory);
  if (runs.empty()) {
    std::cerr << "uampc experiment: all " << snapshot.plan.size() << " runs finished before; nothing to submit\n";
    return {collectRuns(snapshot, output_directory)};
  }
  const std::string job = submit(runs, output_directory, options, snapshot.experiment.name);
  if (job.empty()) return {std::nullopt, 2};
  std::cerr << "uampc experiment: submitted slurm job " << job << ", " << runs.size() << " array task(s) of "
            << snapshot.plan.size() << " runs" << (runs.size() < snapshot.plan.size() ? " (the rest finished before)" : "")
            << "; task output in " << (slurmDirectory(output_directory) / ("task-" + job + "_<K>.out")).string() << "\n";
  if (!options.wait) {
    std::cerr << "uampc experiment: not watching (--no-wait); results once it ends: uampc experiment --collect "
              << output_directory << "\n";
    return {std::nullopt, 0};
  }
  if (!watch(snapshot, runs, job, output_directory, options)) return {std::nullopt, 130};
  const std::string states = finalStates(job, output_directory);
  if (!states.empty()) std::cerr << "uampc experiment: slurm job " << job << " ended (" << states << ")\n";
  return {collectRuns(snapshot, output_directory)};
}

}  // namespace uampc::app
