// The instruction set that vectorised code runs with, picked at run time: AVX2 where the CPU
// has it, SSE2 (every x86-64 CPU; the compiler's generic vectors elsewhere) otherwise, and a
// scalar path. Every path computes the same products and sums element by element in the same
// order, so their results are identical (FMA is never used: a fused product rounds once
// instead of twice and would change the answers).
//
// The environment variable DSS_SIMD (scalar, sse2 or avx2) forces a path for a process (a path
// the CPU lacks falls back to the best one it has); an unknown value is ignored.
#pragma once

/// Compiles a function for AVX2 (its callers pick it only where activeSimdPath() is kAvx2);
/// nothing where the compiler does not target x86, whose AVX2 path then runs the generic code.
#if defined(__x86_64__) || defined(__i386__)
#define DSS_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define DSS_TARGET_AVX2
#endif

namespace dss {

enum class SimdPath { kScalar, kSse2, kAvx2 };

/// The best path this CPU runs.
SimdPath bestSimdPath();
/// The path to use: DSS_SIMD when set (and available), else bestSimdPath(). Read once.
SimdPath activeSimdPath();
/// True when this CPU (and this build) can run `path`.
bool simdPathAvailable(SimdPath path);
/// "scalar", "sse2" or "avx2".
const char* simdPathName(SimdPath path);

}  // namespace dss
