// A shape held by reference: models keep their shapes (a hull may hold thousands of points)
// and a query poses them without a copy. Ref forwards the shape's support and traits, so
// that Posed<Ref<S>> takes the same shortcuts as Posed<S> (a ball's rotation is skipped).
#pragma once

#include "dss/core/posed.h"
#include "dss/core/types.h"

namespace dss::detail {

template <class S>
struct Ref {
  using Scalar = decltype(std::declval<const S&>().magnitude());
  const S& s;
  static constexpr bool kExactVertices = false;
  static constexpr bool kRotationInvariant = RotationInvariant<S>::value;
  static constexpr bool kCenteredAtOrigin = CenteredAtOrigin<S>::value;
  DSS_INLINE Vec3<Scalar> support(const Vec3<Scalar>& d, const Vec3<Scalar>& shift) const {
    return s.support(d, shift);
  }
  Vec3<Scalar> center() const { return s.center(); }
  Vec3<Scalar> anchor() const { return s.anchor(); }
  Scalar magnitude() const { return s.magnitude(); }
};

/// The shape behind a Ref (or the shape itself).
template <class S>
const S& unref(const S& s) {
  return s;
}
template <class S>
const S& unref(const Ref<S>& r) {
  return r.s;
}

}  // namespace dss::detail
