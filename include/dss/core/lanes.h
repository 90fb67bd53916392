// Eight float lanes (one AVX register in a function compiled for AVX2, two SSE2 registers
// otherwise) and the helpers the batched passes share: kinematics_batch.h and state_batch.h
// compute one state per lane with the compiler's generic vectors, element by element.
//
// Arithmetic and bitwise operations on the 256-bit vectors compile to two 128-bit operations
// where the target has no 256-bit vectors (the generic build: SSE2, NEON), but comparisons and
// selections by `?:` compile lane by lane there, with branches. The batched passes therefore
// compare through less() and the like, which take `wide` (the function is compiled for AVX2)
// and otherwise compare the two halves four lanes at a time, and select by select(): the same
// results either way.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace dss::lanes {

constexpr int kLanes = 8;
using F8 = float __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));
/// Four double lanes, and their comparisons' masks.
using D4 = double __attribute__((vector_size(32)));
using L4 = std::int64_t __attribute__((vector_size(32)));

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

namespace detail {
using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));
using D2 = double __attribute__((vector_size(16)));
using L2 = std::int64_t __attribute__((vector_size(16)));
template <class Half, class Whole>
__attribute__((always_inline)) inline void split(const Whole& w, Half& lo, Half& hi) {
  static_assert(2 * sizeof(Half) == sizeof(Whole));
  std::memcpy(&lo, &w, sizeof lo);
  std::memcpy(&hi, reinterpret_cast<const char*>(&w) + sizeof lo, sizeof hi);
}
template <class Whole, class Half>
__attribute__((always_inline)) inline Whole join(const Half& lo, const Half& hi) {
  static_assert(2 * sizeof(Half) == sizeof(Whole));
  Whole w;
  std::memcpy(&w, &lo, sizeof lo);
  std::memcpy(reinterpret_cast<char*>(&w) + sizeof lo, &hi, sizeof hi);
  return w;
}
/// op(a, b) per lane: on the whole vectors where `wide`, else on their two halves.
template <class Mask, class HalfMask, class Half, class Whole, class Op>
__attribute__((always_inline)) inline Mask compare(Whole a, Whole b, bool wide, Op op) {
  if (wide) return op(a, b);
  Half a0, a1, b0, b1;
  split(a, a0, a1);
  split(b, b0, b1);
  return join<Mask>(HalfMask(op(a0, b0)), HalfMask(op(a1, b1)));
}
}  // namespace detail

/// a < b per lane: all ones where true, else zero (false for NaN).
__attribute__((always_inline)) inline I8 less(F8 a, F8 b, bool wide) {
  return detail::compare<I8, detail::I4, detail::F4>(a, b, wide, std::less<>());
}
__attribute__((always_inline)) inline I8 less(I8 a, I8 b, bool wide) {
  return detail::compare<I8, detail::I4, detail::I4>(a, b, wide, std::less<>());
}
__attribute__((always_inline)) inline L4 lessEqual(D4 a, D4 b, bool wide) {
  return detail::compare<L4, detail::L2, detail::D2>(a, b, wide, std::less_equal<>());
}
/// a > b per lane.
__attribute__((always_inline)) inline I8 greater(F8 a, F8 b, bool wide) { return less(b, a, wide); }
__attribute__((always_inline)) inline I8 greater(I8 a, I8 b, bool wide) { return less(b, a, wide); }
/// a where mask m is all ones, b where it is zero.
__attribute__((always_inline)) inline F8 select(I8 m, F8 a, F8 b, bool wide) {
  if (wide) return m ? a : b;
  return (F8)(((I8)a & m) | ((I8)b & ~m));
}
__attribute__((always_inline)) inline D4 select(L4 m, D4 a, D4 b, bool wide) {
  if (wide) return m ? a : b;
  return (D4)(((L4)a & m) | ((L4)b & ~m));
}
/// |v| per lane, by its sign bit (NaN stays NaN; -0 becomes +0, which compares and sums as -0
/// does wherever the passes use it).
__attribute__((always_inline)) inline F8 abs(F8 v) {
  return (F8)((I8)v & std::int32_t(0x7fffffff));
}
__attribute__((always_inline)) inline D4 abs(D4 v) {
  return (D4)((L4)v & std::int64_t(0x7fffffffffffffff));
}

#pragma GCC diagnostic pop

}  // namespace dss::lanes
