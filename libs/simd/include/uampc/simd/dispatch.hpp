// Two builds of a hot loop, one process-wide choice between them.
//
// The libraries are compiled for the x86-64 baseline (SSE2: 4 floats or 2 doubles per
// instruction) so that they run on any x86-64 machine. A loop that vectorises can also be compiled
// for AVX2 (8 floats or 4 doubles) inside the same library and picked at run time:
//
//   UAMPC_SIMD_INLINE void kernelBody(...) { ... }                // the loop, written once
//   void kernelBaseline(...) { kernelBody(...); }                 // SSE2
//   UAMPC_SIMD_AVX2 void kernelAvx2(...) { kernelBody(...); }      // AVX2, where the CPU has it
//   void kernel(...) { simd::avx2() ? kernelAvx2(...) : kernelBaseline(...); }
//
// Both give the same bits, which keeps lockstep runs identical from one machine to the next: the
// operations that vectorise here (+ - * /, sqrt, min/max, compares, conversions) are exactly
// rounded IEEE operations in any vector width, floating-point code is compiled without
// -ffast-math (no reassociation), and AVX2 alone does not enable FMA, so nothing is contracted
// into a fused multiply-add. Loops that sum in a different order when widened (reductions) do not
// belong here. Each kernel's test compares its two builds bit for bit.
//
// UAMPC_SIMD=baseline in the environment forces the baseline (to compare, or to rule it out);
// unset, empty or "auto" lets the CPU decide; any other value is reported on stderr and ignored.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define UAMPC_SIMD_HAS_AVX2 1
#define UAMPC_SIMD_AVX2 __attribute__((target("avx2")))
#else
#define UAMPC_SIMD_HAS_AVX2 0
#define UAMPC_SIMD_AVX2
#endif
// The body is inlined into each build, where it is compiled for that build's instruction set.
#if defined(__GNUC__) || defined(__clang__)
#define UAMPC_SIMD_INLINE inline __attribute__((always_inline))
#else
#define UAMPC_SIMD_INLINE inline
#endif

namespace uampc::simd {

// True when the AVX2 builds run: the CPU has AVX2 and UAMPC_SIMD is not "baseline". Decided on
// the first call, then constant for the process.
bool avx2();

// Whether the CPU has AVX2, whatever UAMPC_SIMD says (tests use it to run both builds).
bool cpuHasAvx2();

// "avx2" or "baseline": what avx2() chose, for benchmarks' output.
const char* instructionSetName();

}  // namespace uampc::simd
