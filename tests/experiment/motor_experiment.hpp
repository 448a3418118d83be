// A one-run experiment for the tests of what counts as done and of whose --out it is: the motor
// at constant speed with the evaluator (tests/scenes/motor_evaluator.yaml), which starts in under
// a second and writes metrics.json at its end.
#pragma once

#include <sys/types.h>

#include <string>

namespace uampc::test {

struct MotorExperiment {
  std::string file;  // DIR/experiment.yaml
  std::string out;   // DIR/out
  std::string run;   // its one run's directory
  int domain = -1;   // the DDS domain its run gets (--jobs 1 --domain-base domain)

  // `experiment FILE --out OUT --jobs 1 --domain-base DOMAIN`, for runUampc or startUampc.
  std::string command() const;
};

// Writes DIR/experiment.yaml: `duration` simulated seconds; `paced` runs them in real time
// (clock.real_time_factor=1), for a test that acts while the run runs. `domain_index` in the
// experiment tests' block (test_domains.hpp).
MotorExperiment motorExperiment(const std::string& dir, double duration, bool paced, int domain_index);

// The pid of the `uampc launch` running on `domain`; -1 when there is none.
pid_t launcherOnDomain(int domain);

// Whether the run's launcher has started stepping (its run.log shows simulated time).
bool runIsStepping(const MotorExperiment& experiment);

}  // namespace uampc::test
