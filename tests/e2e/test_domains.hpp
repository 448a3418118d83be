// The DDS domains the tests run on, from one list. ctest runs test executables in parallel (-j2 in
// CI), and two runs on one domain hear each other's clock and topics: a lockstep run then waits
// for acknowledgements meant for the other and fails after clock.ack_timeout. So each test
// executable that starts DDS participants owns a block of domains, given by its place below, and
// numbers its runs within the block.
#pragma once

#include <stdexcept>
#include <string>

namespace uampc::test {

enum class DomainBlock {
  kLockstep = 1,  // block 0 (domains 0..) stays free for a user's run beside the tests
  kSupervision,
  kSimulator,
  kLoop,
  kLoDrift,
  kTf,
  kRunInfo,
  kRecordReplay,
  kWireFormat,
  kTopicTools,  // uampc topic (index 0) and the live viewer (1..)
  kExperimentE2e,
  kSceneValidation,
  kDdsProfile,
  kFaults,
  kSecurity,
  kDynamixel,
  kRigScene,
  kSlurmExperiment,
  kSpeedTargets,  // tests/speed_targets (Python): index 0 only, 228 (Fast DDS's domains end at 232)
};

inline constexpr int kDomainsPerTest = 12;

// Throws (a compile error where used in a constant expression) when a test needs more domains
// than its block has.
constexpr int testDomain(DomainBlock block, int index) {
  if (index < 0 || index >= kDomainsPerTest) throw std::out_of_range("testDomain: index outside the block");
  return static_cast<int>(block) * kDomainsPerTest + index;
}

// " --set domain_id=N" for a launch command line.
inline std::string domainOverride(DomainBlock block, int index) {
  return " --set domain_id=" + std::to_string(testDomain(block, index));
}

}  // namespace uampc::test
