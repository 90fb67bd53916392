// Construction of the core shapes of a pair file and the loop over the library's decisions.
#include "pairs_shapes.h"

#include <stdexcept>

#include "dss/comparisons/any_shape_comparisons.h"
#include "dss/core/any_shape_query.h"

namespace dss {
namespace pairs {
namespace {

void place(const ShapeSpec& s, AnyShape& shape, Eigen::Isometry3d& X_WS) {
  X_WS = Eigen::Isometry3d::Identity();
  switch (s.kind) {
    case ShapeKind::kSphere:
      shape = Sphere{s.radius};
      break;
    case ShapeKind::kBox:
      shape = Box::fromSize(s.dims);
      break;
    case ShapeKind::kCapsule:
      shape = Capsule::fromLength(s.radius, s.length);
      break;
    case ShapeKind::kCylinder:
      shape = Cylinder::fromLength(s.radius, s.length);
      break;
    case ShapeKind::kCone:
      shape = Cone::fromLength(s.radius, s.length);
      break;
    case ShapeKind::kEllipsoid:
      shape = Ellipsoid{s.dims};
      break;
    case ShapeKind::kConvex:
      shape = ConvexHull(s.worldVertices());
      return;  // world points
    default:
      throw std::invalid_argument("unknown shape kind");
  }
  X_WS.linear() = s.R_WS;
  X_WS.translation() = s.p_WS;
}

}  // namespace

CorePair makeCorePair(const ShapeSpec& a, const ShapeSpec& b) {
  CorePair p;
  place(a, p.a, p.X_WA);
  place(b, p.b, p.X_WB);
  return p;
}

void decideAll(CoreAlgo algo, const std::vector<CorePair>& pairs, const Options& opt,
               double padding, std::vector<Result>& out) {
  out.resize(pairs.size());
  auto run = [&](auto&& decide) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const CorePair& p = pairs[i];
      out[i] = decide(p.a, p.X_WA, p.b, p.X_WB, opt, padding);
    }
  };
  using Decide = Result (*)(const AnyShape&, const Eigen::Isometry3d&, const AnyShape&,
                            const Eigen::Isometry3d&, const Options&, double);
  switch (algo) {
    case CoreAlgo::kDss:
      return run(static_cast<Decide>(&intersect));
    case CoreAlgo::kGjk:
      return run(&intersectGjk);
    case CoreAlgo::kHybrid:
      return run(&intersectHybrid);
  }
}

}  // namespace pairs
}  // namespace dss
