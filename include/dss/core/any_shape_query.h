// Pairwise decisions on AnyShape with poses: the shape-type dispatch happens once per pair
// (std::visit), then the decision runs on concrete types.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/dss.h"
#include "dss/core/gjk.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"

namespace dss {

namespace detail {
/// A shape by reference (models keep their hulls; queries do not copy them).
template <class S>
struct Ref {
  const S& s;
  static constexpr bool kExactVertices = false;
  // Forwarded so that posing a referenced ball skips the rotation, as posing the ball would.
  static constexpr bool kRotationInvariant = RotationInvariant<S>::value;
  static constexpr bool kCenteredAtOrigin = CenteredAtOrigin<S>::value;
  Vec3d support(const Vec3d& d, const Vec3d& shift) const { return s.support(d, shift); }
  Vec3d center() const { return s.center(); }
  Vec3d anchor() const { return s.anchor(); }
  double magnitude() const { return s.magnitude(); }
};
}  // namespace detail

enum class Algorithm : std::uint8_t { kDss, kGjk, kHybrid };

template <class A, class B>
Result decide(const A& a, const B& b, const Options& opt, Algorithm algo) {
  switch (algo) {
    case Algorithm::kGjk: return intersectGjk(a, b, opt);
    case Algorithm::kHybrid: return intersectHybrid(a, b, opt);
    default: return intersect(a, b, opt);
  }
}

/// Do shape a at pose X_WA and shape b at pose X_WB intersect? `padding` > 0 grows a by a
/// ball: the answer is then "distance <= padding". Compiled once, in the core library (every
/// pair of shape types, every mode and algorithm): callers do not instantiate the search.
Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt = {}, double padding = 0.0,
                 Algorithm algo = Algorithm::kDss);

}  // namespace dss
