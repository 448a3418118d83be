#include "uampc/simd/dispatch.hpp"

#include <cstdio>
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
// UAMPC_SIMD: unset, empty or "auto" lets the CPU decide; "baseline" forces the SSE2 builds.
// Anything else is a typo, said once on stderr (this runs inside a component's first control
// step or scan, where throwing would stop a run over a setting that cannot change its results).
bool chooseAvx2() {
  const char* setting = std::getenv("UAMPC_SIMD");
  if (setting != nullptr && std::strcmp(setting, "baseline") == 0) return false;
  if (setting != nullptr && *setting != '\0' && std::strcmp(setting, "auto") != 0) {
    std::fprintf(stderr, "uampc: UAMPC_SIMD=%s is not one of: auto, baseline; using auto\n", setting);
  }
  return cpuHasAvx2();
}
}  // namespace

bool avx2() {
  static const bool chosen = chooseAvx2();
  return chosen;
}

const char* instructionSetName() { return avx2() ? "avx2" : "baseline"; }

}  // namespace uampc::simd
