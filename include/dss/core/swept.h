// The convex hull of two posed copies of one shape: conv(X_0(S) U X_1(S)).
//
// Its support is the better of the two copies' supports. For a pure translation it is the
// exact swept volume; for a motion with rotation it is the base that a conservative motion
// check pads by a bound on how far the rotation can bulge (see dss/planning).
#pragma once

#include "dss/core/types.h"

namespace dss {

template <class S>
struct SweptHull {
  using Scalar = decltype(std::declval<S>().magnitude());
  static constexpr bool kExactVertices = false;

  S shape;
  Mat3<Scalar> R0 = Mat3<Scalar>::Identity(), R1 = Mat3<Scalar>::Identity();
  Vec3<Scalar> p0 = Vec3<Scalar>::Zero(), p1 = Vec3<Scalar>::Zero();

  DSS_INLINE Vec3<Scalar> support(const Vec3<Scalar>& d, const Vec3<Scalar>& shift) const {
    const Vec3<Scalar> x0 =
        R0 * shape.support(R0.transpose() * d, Vec3<Scalar>::Zero()) + (p0 - shift);
    const Vec3<Scalar> x1 =
        R1 * shape.support(R1.transpose() * d, Vec3<Scalar>::Zero()) + (p1 - shift);
    return d.dot(x1) > d.dot(x0) ? x1 : x0;
  }
  Vec3<Scalar> center() const {
    return Scalar(0.5) * ((R0 * shape.center() + p0) + (R1 * shape.center() + p1));
  }
  Vec3<Scalar> anchor() const { return p0; }
  Scalar magnitude() const { return shape.magnitude() + (p1 - p0).stableNorm(); }
};

}  // namespace dss
