// A shape placed in the world by a rigid pose: x_W = R_WS * x_S + p_WS.
//
// The support of a posed shape rotates the direction into the shape's frame and the point
// back out. `shift` is subtracted from the translation before the rotated point is added,
// so that two shapes far from the origin are compared in a frame near them.
#pragma once

#include <type_traits>

#include "dss/core/types.h"

namespace dss {
namespace detail {
// Shapes may declare `static constexpr bool kRotationInvariant = true` (a ball: its support
// does not depend on the rotation of its frame) and `kCenteredAtOrigin = true` (center() is
// the origin); posing then skips the work they make unnecessary.
template <class S, class = void>
struct RotationInvariant : std::false_type {};
template <class S>
struct RotationInvariant<S, std::void_t<decltype(S::kRotationInvariant)>>
    : std::integral_constant<bool, S::kRotationInvariant> {};
template <class S, class = void>
struct CenteredAtOrigin : std::false_type {};
template <class S>
struct CenteredAtOrigin<S, std::void_t<decltype(S::kCenteredAtOrigin)>>
    : std::integral_constant<bool, S::kCenteredAtOrigin> {};
}  // namespace detail

template <class S>
struct Posed {
  using Scalar = decltype(std::declval<S>().magnitude());
  static constexpr bool kExactVertices = false;

  S shape;
  Mat3<Scalar> R_WS = Mat3<Scalar>::Identity();
  Vec3<Scalar> p_WS = Vec3<Scalar>::Zero();

  Posed() = default;
  Posed(S s, const Mat3<Scalar>& R, const Vec3<Scalar>& p)
      : shape(std::move(s)), R_WS(R), p_WS(p) {}

  DSS_INLINE Vec3<Scalar> support(const Vec3<Scalar>& d_W, const Vec3<Scalar>& shift) const {
    const Vec3<Scalar> zero(Scalar(0), Scalar(0), Scalar(0));
    if constexpr (detail::RotationInvariant<S>::value) {
      return detail::sum3(shape.support(d_W, zero), detail::diff3(p_WS, shift));
    }
    // Written out, scalar by scalar: in large translation units GCC leaves Eigen's fixed-size
    // products out of line here (a call each way).
    const Mat3<Scalar>& R = R_WS;
    const Vec3<Scalar> d_S(R(0, 0) * d_W.x() + R(1, 0) * d_W.y() + R(2, 0) * d_W.z(),
                           R(0, 1) * d_W.x() + R(1, 1) * d_W.y() + R(2, 1) * d_W.z(),
                           R(0, 2) * d_W.x() + R(1, 2) * d_W.y() + R(2, 2) * d_W.z());
    const Vec3<Scalar> x = shape.support(d_S, zero);
    return Vec3<Scalar>(
        R(0, 0) * x.x() + R(0, 1) * x.y() + R(0, 2) * x.z() + (p_WS.x() - shift.x()),
        R(1, 0) * x.x() + R(1, 1) * x.y() + R(1, 2) * x.z() + (p_WS.y() - shift.y()),
        R(2, 0) * x.x() + R(2, 1) * x.y() + R(2, 2) * x.z() + (p_WS.z() - shift.z()));
  }
  Vec3<Scalar> center() const {
    if constexpr (detail::CenteredAtOrigin<S>::value) return p_WS;
    return R_WS * shape.center() + p_WS;
  }
  Vec3<Scalar> anchor() const { return p_WS; }
  Scalar magnitude() const { return shape.magnitude(); }
};

template <class S, class T>
Posed<S> posed(S s, const Mat3<T>& R, const Vec3<T>& p) {
  return Posed<S>(std::move(s), R, p);
}

}  // namespace dss
