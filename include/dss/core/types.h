// Basic linear-algebra aliases shared by the whole core. The core is templated on the
// scalar type so that the same code runs in `double` (default, and the base of the exact
// mode) and in `float` (the paper's arithmetic).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

// The search is one function per instantiation (DSS_NOINLINE); its leaves -- supports, vector
// arithmetic, the polygon update -- are forced inline into it (DSS_INLINE): left out of line,
// a call boundary spills every vector to memory. Sanitizer builds (and DSS_NO_FORCE_INLINE)
// leave the choice to the compiler, which keeps instrumented builds fast to compile.
#if (defined(__GNUC__) || defined(__clang__)) && !defined(__SANITIZE_ADDRESS__) && \
    !defined(DSS_NO_FORCE_INLINE)
#define DSS_INLINE inline __attribute__((always_inline))
#define DSS_NOINLINE __attribute__((noinline))
#else
#define DSS_INLINE inline
#define DSS_NOINLINE
#endif

namespace dss {

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;
using Vec3f = Vec3<float>;

namespace detail {
// The query loop's vector arithmetic, written out. Eigen's fixed-size operations are plain
// `inline` templates several layers deep; in a large translation unit GCC's inliner runs out
// of budget and leaves some of them as calls (squaredNorm, negation, assignment) inside the
// loop. These are leaves, forced inline.
template <class T>
DSS_INLINE T dot3(const Vec3<T>& a, const Vec3<T>& b) {
  return a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}
template <class T>
DSS_INLINE Vec3<T> cross3(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(),
                 a.x() * b.y() - a.y() * b.x());
}
template <class T>
DSS_INLINE Vec3<T> scaled3(const Vec3<T>& a, T s) {
  return Vec3<T>(a.x() * s, a.y() * s, a.z() * s);
}
template <class T>
DSS_INLINE Vec3<T> sum3(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a.x() + b.x(), a.y() + b.y(), a.z() + b.z());
}
template <class T>
DSS_INLINE Vec3<T> diff3(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a.x() - b.x(), a.y() - b.y(), a.z() - b.z());
}
template <class T>
DSS_INLINE Vec3<T> neg3(const Vec3<T>& a) {
  return Vec3<T>(-a.x(), -a.y(), -a.z());
}
template <class T>
DSS_INLINE T norm1_3(const Vec3<T>& a) {  // |a|_1, an upper bound of |a| without a square root
  return std::abs(a.x()) + std::abs(a.y()) + std::abs(a.z());
}
template <class T>
DSS_INLINE bool isZero3(const Vec3<T>& a) {
  return a.x() == T(0) && a.y() == T(0) && a.z() == T(0);
}

/// Supports that square their direction take it as it is while its squared norm stays in
/// [kSafeLow, kSafeHigh] (the usual case, in float and double) and through powerOfTwoScaled
/// otherwise.
inline constexpr double kSafeLow = 1e-30, kSafeHigh = 1e30;

/// d times the power of two that brings its largest |component| into [1, 2): the same
/// direction (exactly, but for components more than about 2^1000 smaller than the largest),
/// with a squared norm that can neither overflow nor vanish. Zero and non-finite vectors come
/// back unchanged. For the rare directions outside the safe range: it calls libm.
template <class T>
Vec3<T> powerOfTwoScaled(const Vec3<T>& d) {
  const T m = std::max(std::abs(d.x()), std::max(std::abs(d.y()), std::abs(d.z())));
  if (!(m > T(0)) || !std::isfinite(m)) return d;
  const int e = std::ilogb(m);
  return Vec3<T>(std::ldexp(d.x(), -e), std::ldexp(d.y(), -e), std::ldexp(d.z(), -e));
}
}  // namespace detail

}  // namespace dss
