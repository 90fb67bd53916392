// Basic linear-algebra aliases shared by the whole core. The core is templated on the
// scalar type so that the same code runs in `double` (default, and the base of the exact
// mode) and in `float` (the paper's arithmetic).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

// The query loop is a handful of small functions (support, polygon update); compilers
// sometimes leave them out of line, and the call boundary then spills every vector to memory.
// Sanitizer builds (and DSS_NO_FORCE_INLINE) leave the choice to the compiler: forcing the
// whole search into every shape pair's instantiation makes instrumented builds very slow.
#if (defined(__GNUC__) || defined(__clang__)) && !defined(__SANITIZE_ADDRESS__) && !defined(DSS_NO_FORCE_INLINE)
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

}  // namespace dss
