#include "uampc/simd/dispatch.hpp"

#include <cstdlib>
#include <cstring>

namespace uampc::simd {

bool cpuHasAvx2() {
#if UAMPC_SIMD_HAS_AVX2
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

namespace {
bool chooseAvx2() {
  const char* forced = std::getenv("UAMPC_SIMD");
  if (forced != nullptr && std::strcmp(forced, "baseline") == 0) return false;
  return cpuHasAvx2();
}
}  // namespace

bool avx2() {
  static const bool chosen = chooseAvx2();
  return chosen;
}

const char* instructionSetName() { return avx2() ? "avx2" : "baseline"; }

}  // namespace uampc::simd
