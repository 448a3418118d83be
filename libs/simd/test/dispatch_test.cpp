#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "uampc/simd/dispatch.hpp"

namespace {

// The CPU's own account: the "flags" line of /proc/cpuinfo (Linux).
bool cpuinfoListsAvx2() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::string flag;
    while (words >> flag) {
      if (flag == "avx2") return true;
    }
    return false;
  }
  return false;
}

TEST(SimdDispatch, DetectsWhatTheCpuReports) {
#if UAMPC_SIMD_HAS_AVX2 && defined(__linux__)
  EXPECT_EQ(uampc::simd::cpuHasAvx2(), cpuinfoListsAvx2());
#else
  EXPECT_FALSE(uampc::simd::cpuHasAvx2());
#endif
}

// The choice is made once per process, on the first call: this test makes it.
TEST(SimdDispatch, EnvironmentForcesTheBaseline) {
  ASSERT_EQ(setenv("UAMPC_SIMD", "baseline", 1), 0);
  EXPECT_FALSE(uampc::simd::avx2());
  EXPECT_STREQ(uampc::simd::instructionSetName(), "baseline");
  ASSERT_EQ(setenv("UAMPC_SIMD", "auto", 1), 0);
  EXPECT_FALSE(uampc::simd::avx2()) << "the choice is constant for the process";
}

}  // namespace
