// Run-time choice of the vector instruction set (see dss/core/simd_path.h).
#include "dss/core/simd_path.h"

#include <cstdlib>
#include <cstring>
#include <initializer_list>

namespace dss {

bool simdPathAvailable(SimdPath path) {
  switch (path) {
    case SimdPath::kScalar:
    case SimdPath::kSse2:
      return true;
    case SimdPath::kAvx2:
#if defined(__x86_64__) || defined(__i386__)
      return __builtin_cpu_supports("avx2");
#else
      return false;
#endif
  }
  return false;
}

SimdPath bestSimdPath() {
  return simdPathAvailable(SimdPath::kAvx2) ? SimdPath::kAvx2 : SimdPath::kSse2;
}

SimdPath activeSimdPath() {
  static const SimdPath path = [] {
    const char* env = std::getenv("DSS_SIMD");
    if (env)
      for (SimdPath p : {SimdPath::kScalar, SimdPath::kSse2, SimdPath::kAvx2})
        if (std::strcmp(env, simdPathName(p)) == 0 && simdPathAvailable(p)) return p;
    return bestSimdPath();
  }();
  return path;
}

const char* simdPathName(SimdPath path) {
  switch (path) {
    case SimdPath::kScalar:
      return "scalar";
    case SimdPath::kSse2:
      return "sse2";
    case SimdPath::kAvx2:
      return "avx2";
  }
  return "?";
}

}  // namespace dss
