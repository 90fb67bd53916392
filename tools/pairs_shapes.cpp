// Construction of the core shapes of a pair file, and their float copies.
#include "pairs_shapes.h"

namespace dss {
namespace pairs {
namespace {

template <class S>
Posed<S> posedPrimitive(S shape, const ShapeSpec& s) {
  return Posed<S>(std::move(shape), s.R_WS, s.p_WS);
}

// Primitive casts, one per type.
template <class U, class T>
SphereT<U> castPrim(const SphereT<T>& s) { return SphereT<U>{U(s.radius)}; }
template <class U, class T>
BoxT<U> castPrim(const BoxT<T>& s) { return BoxT<U>{s.half.template cast<U>()}; }
template <class U, class T>
CapsuleT<U> castPrim(const CapsuleT<T>& s) { return CapsuleT<U>{U(s.radius), U(s.half_length)}; }
template <class U, class T>
CylinderT<U> castPrim(const CylinderT<T>& s) { return CylinderT<U>{U(s.radius), U(s.half_length)}; }
template <class U, class T>
ConeT<U> castPrim(const ConeT<T>& s) { return ConeT<U>{U(s.radius), U(s.half_length)}; }
template <class U, class T>
EllipsoidT<U> castPrim(const EllipsoidT<T>& s) { return EllipsoidT<U>{s.radii.template cast<U>()}; }

template <class U, class S>
auto castAny(const Posed<S>& p) {
  auto prim = castPrim<U>(p.shape);
  return Posed<decltype(prim)>(prim, p.R_WS.template cast<U>(), p.p_WS.template cast<U>());
}
template <class U>
ConvexHullT<U> castAny(const ConvexHull& h) {
  return h.cast<U>();
}
template <class U, class S>
auto castAny(const Padded<S>& p) {
  auto inner = castAny<U>(p.shape);
  return Padded<decltype(inner)>{std::move(inner), U(p.radius)};
}

}  // namespace

ShapeVariant<double> makeShape(const ShapeSpec& s) {
  switch (s.kind) {
    case ShapeKind::kSphere: return posedPrimitive(Sphere{s.radius}, s);
    case ShapeKind::kBox: return posedPrimitive(Box::fromSize(s.dims), s);
    case ShapeKind::kCapsule: return posedPrimitive(Capsule::fromLength(s.radius, s.length), s);
    case ShapeKind::kCylinder:
      return posedPrimitive(Cylinder::fromLength(s.radius, s.length), s);
    case ShapeKind::kCone: return posedPrimitive(Cone::fromLength(s.radius, s.length), s);
    case ShapeKind::kEllipsoid: return posedPrimitive(Ellipsoid{s.dims}, s);
    case ShapeKind::kConvex: return ConvexHull(s.worldVertices());
  }
  throw std::invalid_argument("unknown shape kind");
}

SideAVariant<double> makeSideA(const ShapeSpec& s, double padding) {
  return std::visit(
      [&](auto&& shape) -> SideAVariant<double> {
        if (padding > 0) return padded(std::move(shape), padding);
        return std::move(shape);
      },
      makeShape(s));
}

ShapeVariant<float> toFloat(const ShapeVariant<double>& s) {
  return std::visit([](const auto& x) -> ShapeVariant<float> { return castAny<float>(x); }, s);
}

SideAVariant<float> toFloat(const SideAVariant<double>& s) {
  return std::visit([](const auto& x) -> SideAVariant<float> { return castAny<float>(x); }, s);
}

void decideAll(CoreAlgo algo, const std::vector<CorePair<double>>& pairs, const Options& opt,
               std::vector<Result>& out) {
  switch (algo) {
    case CoreAlgo::kDss: return decideAllDss(pairs, opt, out);
    case CoreAlgo::kGjk: return decideAllGjk(pairs, opt, out);
    case CoreAlgo::kHybrid: return decideAllHybrid(pairs, opt, out);
  }
}

void decideAll(CoreAlgo algo, const std::vector<CorePair<float>>& pairs, const Options& opt,
               std::vector<Result>& out) {
  switch (algo) {
    case CoreAlgo::kDss: return decideAllDss(pairs, opt, out);
    case CoreAlgo::kGjk: return decideAllGjk(pairs, opt, out);
    case CoreAlgo::kHybrid: return decideAllHybrid(pairs, opt, out);
  }
}

}  // namespace pairs
}  // namespace dss
