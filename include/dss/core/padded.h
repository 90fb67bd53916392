// A shape grown by a ball of radius r (Minkowski sum with B(r)).
//
// A and B are at distance >= r exactly when A + B(r) and B do not intersect, so padding
// turns the intersection decision into an exact clearance query with no new algorithm.
#pragma once

#include "dss/core/types.h"

namespace dss {

template <class S>
struct Padded {
  using Scalar = decltype(std::declval<S>().magnitude());
  static constexpr bool kExactVertices = false;

  S shape;
  Scalar radius{0};

  DSS_INLINE Vec3<Scalar> support(const Vec3<Scalar>& d, const Vec3<Scalar>& shift) const {
    Vec3<Scalar> x = shape.support(d, shift);
    const Scalar n2 = d.squaredNorm();
    if (n2 > Scalar(detail::kSafeLow) && n2 < Scalar(detail::kSafeHigh))
      return x + d * (radius / std::sqrt(n2));
    // A direction whose square overflows or vanishes: the ball's point from the direction
    // scaled by a power of two (d == 0: nothing to add).
    const Vec3<Scalar> u = detail::powerOfTwoScaled(d);
    const Scalar n = u.norm();
    if (n > Scalar(0)) x += u * (radius / n);
    return x;
  }
  Vec3<Scalar> center() const { return shape.center(); }
  Vec3<Scalar> anchor() const { return shape.anchor(); }
  Scalar magnitude() const { return shape.magnitude() + radius; }
};

template <class S, class T>
Padded<S> padded(S s, T r) {
  return Padded<S>{std::move(s), r};
}

}  // namespace dss
