#include "motor_experiment.hpp"

#include <fstream>
#include <sstream>

#include "../e2e/background_launch.hpp"
#include "../e2e/command_runner.hpp"
#include "../e2e/test_domains.hpp"

namespace uampc::test {

std::string MotorExperiment::command() const {
  return "experiment " + file + " --out " + out + " --jobs 1 --domain-base " + std::to_string(domain);
}

MotorExperiment motorExperiment(const std::string& dir, double duration, bool paced, int domain_index) {
  MotorExperiment e;
  e.file = dir + "/experiment.yaml";
  e.out = dir + "/out";
  e.run = e.out + "/runs/motor/constant/seed1";
  e.domain = testDomain(DomainBlock::kExperimentE2e, domain_index);
  std::ostringstream overrides;
  overrides << "[clock.duration=" << duration << (paced ? ", clock.real_time_factor=1" : "") << "]";
  std::ofstream(e.file) << "name: motor\nseeds: [1]\nscenes:\n  - {name: motor, scene: "
                        << sourcePath("tests/scenes/motor_evaluator.yaml") << ", overrides: " << overrides.str()
                        << "}\ncontrollers:\n  - {name: constant, overrides: []}\n";
  return e;
}

pid_t launcherOnDomain(int domain) {
  // [u] keeps the shell that runs pgrep from matching its own command line.
  const std::string pattern = "[u]ampc launch .*domain_id=" + std::to_string(domain) + "( |$)";
  std::istringstream pids(runShell("pgrep -f '" + pattern + "'").output);
  pid_t pid = -1;
  pids >> pid;
  return pid;
}

bool runIsStepping(const MotorExperiment& experiment) { return logHas(experiment.run + "/run.log", "uampc: sim "); }

}  // namespace uampc::test
