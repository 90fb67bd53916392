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
    const Scalar n = d.norm();
    Vec3<Scalar> x = shape.support(d, shift);
    if (n > Scalar(0)) x += d * (radius / n);
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
