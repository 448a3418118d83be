// The wire format: a PointCloud2 and an Odometry published by uampc over Fast DDS are received and
// decoded field by field by a Cyclone DDS subscriber built from its own IDL (tests/wire/).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "command_runner.hpp"
#include "test_domains.hpp"

namespace uampc::test {
namespace {

TEST(WireFormat, CycloneDdsDecodesOurPointCloud2AndOdometry) {
  constexpr int kDomain = testDomain(DomainBlock::kWireFormat, 0);
  const pid_t publisher = fork();
  ASSERT_GE(publisher, 0);
  if (publisher == 0) {
    const std::string cmd = "exec env UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " +
                            binaryPath("bin/uampc") + " launch " + sourcePath("tests/scenes/wire_publisher.yaml") +
                            " --set domain_id=" + std::to_string(kDomain) + " > /dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const CommandResult r = runShell(binaryPath("tests/cyclone_subscriber") + " " + std::to_string(kDomain) + " 30");
  kill(publisher, SIGINT);
  int status = 0;
  waitpid(publisher, &status, 0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("PointCloud2 and Odometry decoded, 0 mismatches"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
