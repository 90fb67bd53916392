// A closed set of shape types for models (robots, scenes), with a pairwise dispatch that is
// resolved once per pair: the decision itself then runs on concrete types, with no virtual
// call or switch per support evaluation.
#pragma once

#include <variant>

#include "dss/core/convex_hull.h"
#include "dss/core/shapes.h"

namespace dss {

using AnyShape = std::variant<Sphere, Box, Capsule, Cylinder, Cone, Ellipsoid, ConvexHull>;

inline const char* shapeTypeName(const AnyShape& s) {
  static constexpr const char* kNames[] = {"sphere", "box",       "capsule", "cylinder",
                                           "cone",   "ellipsoid", "convex"};
  return kNames[s.index()];
}

/// Upper bound of |x| over the shape in its own frame.
inline double shapeMagnitude(const AnyShape& s) {
  return std::visit([](const auto& x) { return double(x.magnitude()); }, s);
}

}  // namespace dss
