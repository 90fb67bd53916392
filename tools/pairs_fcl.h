// FCL 0.7 equivalents of the shapes of a pair file, for `dss_pairs --algo fcl`.
//
// Primitives map to fcl::Sphere, Box, Cylinder, Capsule, Cone (apex at +z, as ours) and
// Ellipsoid with the same pose; a convex point set maps to fcl::Convex in the shape's frame
// with the same pose. fcl::Convex wants faces: the hull is built with qhull (libqhull_r,
// triangulated, outward facets, hull vertices only). Point sets without a 3-D hull (1-3
// points, collinear or coplanar sets, or sets qhull rejects) are handed over as all their
// points with no faces, which FCL accepts: with no faces its support function is a linear
// scan over the points, still exactly the hull's support. Decisions use fcl::collide with a
// default CollisionRequest (GJK solver GST_LIBCCD). Padding by r is a distance query:
// a pair that does not collide intersects when fcl::distance <= r.
#pragma once

#include <fcl/fcl.h>

#include <memory>
#include <vector>

#include "pairs_input.h"

namespace dss {
namespace pairs {

struct FclShape {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  fcl::Transform3d X_WS = fcl::Transform3d::Identity();
  bool hull_is_3d = true;  // convex: false when the degenerate fallback was used
};

struct FclPair {
  FclShape a, b;
};

FclShape makeFclShape(const ShapeSpec& s);

/// True when the shapes collide (or, with padding > 0, are at distance <= padding).
bool fclIntersect(const FclPair& p, double padding);

}  // namespace pairs
}  // namespace dss
