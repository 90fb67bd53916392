// A chain of balls along a collision element, looked up in the clearance grid: points on the
// longest axis of the element's local box, each with an outer radius (its ball holds the part
// of the shape in its slab of the box, so that the balls together hold the shape) and an inner
// radius (its ball lies inside the shape). A long element (a beam, a forearm) is covered far
// more tightly by its chain than by its one bounding sphere.
//
// The sweep (sweep.h) asks the grid about each point of a link whose own sphere it could not
// clear: every outer ball of an element clear proves the element clear of the scene, and an
// inner ball within the padding of an obstacle proves a collision.
#pragma once

#include <Eigen/Core>

#include "dss/core/any_shape.h"

namespace dss {

struct SphereChain {
  static constexpr int kMaxPoints = 8;
  int num_points = 0;
  Eigen::Vector3d center_S[kMaxPoints];  ///< in the shape frame
  double outer[kMaxPoints] = {};         ///< the ball holds the shape's part in the point's slab
  double inner[kMaxPoints] = {};         ///< the ball lies inside the shape (0: none)
};

/// The chain of `shape`, whose local box is (box_c, box_h) (element_bounds.h): the box's
/// longest axis cut into as many equal slabs as it is longer than the next axis (1 to
/// kMaxPoints), a point at the centre of each. Outer radii: exact for hulls (the farthest
/// vertex of the hull cut by the slab) and for cylinders along their axis, the slab's corners
/// for the other shapes, and a single point keeps the bounding sphere (element_bounds.h)
/// when smaller; grown by a relative 1e-9 like the local box. Inner radii: innerRadii
/// (inner_shapes.h).
SphereChain sphereChain(const AnyShape& shape, const Eigen::Vector3d& box_c,
                        const Eigen::Vector3d& box_h);

}  // namespace dss
