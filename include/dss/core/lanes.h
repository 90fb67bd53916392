// Eight float lanes (one AVX register in a function compiled for AVX2, two SSE2 registers
// otherwise) and the helpers the batched passes share: kinematics_batch.h and state_batch.h
// compute one state per lane with the compiler's generic vectors, element by element.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace dss::lanes {

constexpr int kLanes = 8;
using F8 = float __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
__attribute__((always_inline)) inline F8 load(const float* p) {
  F8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
__attribute__((always_inline)) inline void store(float* p, F8 v) { std::memcpy(p, &v, sizeof v); }
__attribute__((always_inline)) inline F8 broadcast(float x) { return F8{} + x; }
/// Bit l set where lane l of a comparison's result m is all ones (lanes are 0 or all ones).
__attribute__((always_inline)) inline unsigned laneBits(I8 m) {
#if defined(__SSE2__)
  __m128 lo, hi;  // the sign bits, four lanes at a time
  std::memcpy(&lo, &m, sizeof lo);
  std::memcpy(&hi, reinterpret_cast<const char*>(&m) + sizeof lo, sizeof hi);
  return unsigned(_mm_movemask_ps(lo)) | (unsigned(_mm_movemask_ps(hi)) << 4);
#else
  std::int32_t v[kLanes];
  std::memcpy(v, &m, sizeof v);
  unsigned bits = 0;
  for (int l = 0; l < kLanes; ++l) bits |= unsigned(v[l] != 0) << l;
  return bits;
#endif
}
#pragma GCC diagnostic pop

}  // namespace dss::lanes
