// Primitive convex shapes, each described only by its support function in its own frame.
//
// Contract shared by every shape type S<T> of the core (primitives here, ConvexHull,
// Posed, Padded and SweptHull in their own headers):
//   Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const
//       a point x of the shape maximising d·x, minus `shift`. `d` need not be unit; for
//       d = 0 any point of the shape is returned. Posed shapes subtract `shift` from
//       their translation before adding the rotated local point, which is what lets the
//       decision work in a frame centred between the two shapes (large offsets cancel
//       exactly where they can).
//   Vec3<T> center() const      a point of the shape (interior when it has one).
//   Vec3<T> anchor() const      the translation a pose adds (zero for unposed shapes).
//   T magnitude() const         an upper bound of |x - anchor()| over the shape (need not be
//                               tight: it is cheap); it scales the rounding-error bounds of
//                               the exact mode.
//   static constexpr bool kRotationInvariant, kCenteredAtOrigin   (optional)
//                               a ball's support ignores the rotation of its frame, and a
//                               shape whose center() is its origin says so: Posed skips
//                               the work these make unnecessary.
//   static constexpr bool kExactVertices
//                               true when `support` with a zero shift returns one of the
//                               shape's input points bit for bit (vertex sets given in
//                               world coordinates). The exact mode can then certify
//                               every answer exactly; otherwise "disjoint" answers are
//                               certified and "intersect" answers are exact up to the
//                               rounding of the support points (about 1e-16 of the size).
//
// Dimensions follow URDF: a box by its full edge lengths; cylinder, capsule and cone along
// local z, centred at the origin; the cone's base disc at z = -length/2 and apex at
// z = +length/2 (as fcl::Cone); a capsule is a segment of `length` along z plus `radius`.
// All shapes are closed sets: touching counts as intersecting.
#pragma once

#include <algorithm>
#include <cmath>

#include "dss/core/types.h"

namespace dss {

template <class T>
struct SphereT {
  T radius{0};
  static constexpr bool kExactVertices = false;
  static constexpr bool kRotationInvariant = true;
  static constexpr bool kCenteredAtOrigin = true;
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T n2 = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
    // radius / |d|, as sqrt(n2) * (radius / n2) where nothing can overflow or lose precision
    // (the usual case): the square root and the division then run side by side.
    constexpr T lo = T(detail::kSafeLow), hi = T(detail::kSafeHigh);
    if (n2 > lo && n2 < hi && radius > lo && radius < hi) {
      const T s = std::sqrt(n2) * (radius / n2);
      return Vec3<T>(d.x() * s - shift.x(), d.y() * s - shift.y(), d.z() * s - shift.z());
    }
    // A direction whose square overflows or vanishes is scaled by a power of two first: the
    // result must be the maximiser for every finite d. d == 0: any point will do (the centre).
    const Vec3<T> u = detail::powerOfTwoScaled(d);
    const T n = std::sqrt(u.x() * u.x() + u.y() * u.y() + u.z() * u.z());
    const T s = n > T(0) ? radius / n : T(0);
    return Vec3<T>(u.x() * s - shift.x(), u.y() * s - shift.y(), u.z() * s - shift.z());
  }
  Vec3<T> center() const { return Vec3<T>::Zero(); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return radius; }
};

template <class T>
struct BoxT {
  Vec3<T> half = Vec3<T>::Zero();  // half edge lengths (URDF size / 2)
  static constexpr bool kExactVertices = false;
  static constexpr bool kCenteredAtOrigin = true;
  static BoxT fromSize(const Vec3<T>& size) { return BoxT{size / T(2)}; }
  // The corner on d's side: copysign is a bit operation, where a comparison per axis would be
  // a branch that random directions mispredict half the time. (A zero component may pick
  // either face: both maximise d.x.)
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    return Vec3<T>(std::copysign(half.x(), d.x()) - shift.x(),
                   std::copysign(half.y(), d.y()) - shift.y(),
                   std::copysign(half.z(), d.z()) - shift.z());
  }
  Vec3<T> center() const { return Vec3<T>::Zero(); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  // |half|_1 >= |half|: a bound without a square root (it only scales error bounds).
  T magnitude() const { return half.x() + half.y() + half.z(); }
};

template <class T>
struct CapsuleT {
  T radius{0};
  T half_length{0};
  static constexpr bool kExactVertices = false;
  static constexpr bool kCenteredAtOrigin = true;
  static CapsuleT fromLength(T radius, T length) { return CapsuleT{radius, length / T(2)}; }
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T n2 = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
    if (!(n2 > T(detail::kSafeLow) && n2 < T(detail::kSafeHigh)))
      return ballSupport(detail::powerOfTwoScaled(d), shift);
    return ballSupport(d, shift);
  }
  Vec3<T> center() const { return Vec3<T>::Zero(); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return radius + half_length; }

 private:
  // The end cap on d's side plus radius d/|d|, without a branch (d == 0: the cap's centre).
  DSS_INLINE Vec3<T> ballSupport(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T n = std::sqrt(d.x() * d.x() + d.y() * d.y() + d.z() * d.z());
    const T s = n > T(0) ? radius / n : T(0);
    return Vec3<T>(d.x() * s - shift.x(), d.y() * s - shift.y(),
                   (d.z() * s + std::copysign(half_length, d.z())) - shift.z());
  }
};

template <class T>
struct CylinderT {
  T radius{0};
  T half_length{0};
  static constexpr bool kExactVertices = false;
  static constexpr bool kCenteredAtOrigin = true;
  static CylinderT fromLength(T radius, T length) { return CylinderT{radius, length / T(2)}; }
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T r2 = d.x() * d.x() + d.y() * d.y();
    // d.x == d.y == 0 is fine as it is (the axis point is a maximiser); r2 may underflow to
    // zero for others.
    if (!(r2 < T(detail::kSafeHigh)) ||
        (r2 < T(detail::kSafeLow) && (d.x() != T(0) || d.y() != T(0))))
      return rim(detail::powerOfTwoScaled(Vec3<T>(d.x(), d.y(), T(0))), d.z(), shift);
    return rim(d, d.z(), shift);
  }
  Vec3<T> center() const { return Vec3<T>::Zero(); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return radius + half_length; }

 private:
  DSS_INLINE Vec3<T> rim(const Vec3<T>& d, T dz, const Vec3<T>& shift) const {
    const T r = std::sqrt(d.x() * d.x() + d.y() * d.y());
    const T s = r > T(0) ? radius / r : T(0);
    return Vec3<T>(d.x() * s, d.y() * s, std::copysign(half_length, dz)) - shift;
  }
};

template <class T>
struct ConeT {
  T radius{0};       // of the base disc, at z = -half_length
  T half_length{0};  // apex at z = +half_length
  static constexpr bool kExactVertices = false;
  static ConeT fromLength(T radius, T length) { return ConeT{radius, length / T(2)}; }
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T n2 = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
    if (!(n2 > T(detail::kSafeLow) && n2 < T(detail::kSafeHigh)) && !detail::isZero3(d))
      return apexOrRim(detail::powerOfTwoScaled(d), shift);
    return apexOrRim(d, shift);
  }
  // The centroid of a cone lies a quarter of the way from the base to the apex.
  Vec3<T> center() const { return Vec3<T>(T(0), T(0), -half_length / T(2)); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return radius + half_length; }

 private:
  DSS_INLINE Vec3<T> apexOrRim(const Vec3<T>& d, const Vec3<T>& shift) const {
    const T r = std::sqrt(d.x() * d.x() + d.y() * d.y());
    // apex value d.z*h against the best base-rim value r*radius - d.z*h
    if (d.z() * half_length >= r * radius - d.z() * half_length) {
      return Vec3<T>(T(0), T(0), half_length) - shift;
    }
    const T s = r > T(0) ? radius / r : T(0);
    return Vec3<T>(d.x() * s, d.y() * s, -half_length) - shift;
  }
};

template <class T>
struct EllipsoidT {
  Vec3<T> radii = Vec3<T>::Zero();
  static constexpr bool kExactVertices = false;
  static constexpr bool kCenteredAtOrigin = true;
  DSS_INLINE Vec3<T> support(const Vec3<T>& d, const Vec3<T>& shift) const {
    // x = D (D d / |D d|) with D = diag(radii): D times a unit vector, which cannot overflow.
    Vec3<T> dd = radii.cwiseProduct(d);
    T n2 = dd.squaredNorm();
    if (!(n2 > T(detail::kSafeLow) && n2 < T(detail::kSafeHigh)) && !detail::isZero3(dd)) {
      dd = detail::powerOfTwoScaled(dd);
      n2 = dd.squaredNorm();
    }
    const T n = std::sqrt(n2);
    return (n > T(0) ? Vec3<T>(radii.cwiseProduct(dd / n)) : Vec3<T>::Zero()) - shift;
  }
  Vec3<T> center() const { return Vec3<T>::Zero(); }
  Vec3<T> anchor() const { return Vec3<T>::Zero(); }
  T magnitude() const { return radii.maxCoeff(); }
};

using Sphere = SphereT<double>;
using Box = BoxT<double>;
using Capsule = CapsuleT<double>;
using Cylinder = CylinderT<double>;
using Cone = ConeT<double>;
using Ellipsoid = EllipsoidT<double>;

}  // namespace dss
